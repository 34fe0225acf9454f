"""Edges (issue 90): a theory-only model map's simulated verdict says no run was made; tiny
k and amplitudes are refused with their bound; an exact spectrum of another ring is
refused; a simulated model map's cells too slow for T say so; summary.json echoes inputs."""

import numpy as np
import pytest

from numerics.maps import ModelMapParameters


def _fput_map(**options):
    return ModelMapParameters.from_model("fput", ("beta", [0.8, 1.6]), ("k", [2.6, 2.8]),
                                         0.1, params={"alpha": 1.0}, **options)


def test_a_theory_only_model_store_says_its_simulated_verdict_holds_no_run():
    ds = _fput_map(theory_only=True).new_dataset()
    attrs = ds["verdict_simulated"].attrs
    said = " ".join(str(v) for v in attrs.values())
    assert "a run grew" not in attrs["long_name"]
    assert "not simulated" in attrs["long_name"] and "no run" in attrs["long_name"]
    assert attrs["undetermined"] == "not simulated: no run made"
    # every cell holds -1, the code the words give for "not simulated"
    assert (ds["verdict_simulated"].values == -1).all() and "-1" in said


def test_a_theory_only_store_resumed_by_a_simulated_map_says_it_holds_runs(tmp_path):
    import xarray as xr

    from numerics.maps import run_map

    quiet = dict(workers=1, progress=False, log=lambda *a: None)
    theory = run_map(_fput_map(N=16, theory_only=True, exact=True, t_end=6.0), tmp_path, **quiet)
    assert int(theory.attrs["theory_only"]) == 1
    ds = run_map(_fput_map(N=16, t_end=6.0), tmp_path, **quiet)
    assert ds["done"].values.all()
    back = xr.open_zarr(tmp_path / "map.zarr")
    for d in (ds, back):  # what run_map returns and what the store says
        assert int(d.attrs["theory_only"]) == 0
        assert d["verdict_simulated"].attrs["long_name"].startswith("simulated:")
        assert "no run made" not in d["verdict_simulated"].attrs["long_name"]


def test_a_theorys_verdict_words_speak_of_the_theory_not_of_runs():
    ds = _fput_map(N=64, t_end=100.0).new_dataset()
    for name in ("verdict_semidiscrete", "verdict_exact", "verdict_fourwave"):
        words = ds[name].attrs["verdict_words"]
        assert "run" not in words and "no growth within T" not in words, name
        assert "not predicted yet" in words and "undefined" in words, name


def test_a_simulated_model_store_names_not_simulated_beside_a_run_that_grew_too_little():
    attrs = _fput_map(N=64, t_end=100.0).new_dataset()["verdict_simulated"].attrs
    assert "not simulated yet where done is False" in attrs["undetermined"]
    assert "a run grew, but less than the threshold" in attrs["verdict_words"]
    assert np.int8(-1) in attrs["flag_values"]


# --- tiny k and tiny amplitudes: refused with their bound, not a verdict of rounding ------

def _fput():
    from energy import load_model

    return load_model("fput")  # alpha 0, beta 1, unit masses and springs


def test_a_k_whose_omega_underflows_is_not_called_a_missing_carrier():
    from energy import ModelError
    from numerics.models import nls

    with pytest.raises(ModelError, match=r"k = 1e-300 is below what float64 resolves .*not "
                                         r"a missing carrier.*k \(--k\) >= \S+"):
        nls(_fput(), 1e-300)


def _diatomic_g1(k, m=2.0):
    """g1 of the diatomic FPUT chain's acoustic branch (masses 1 and m, unit springs):
    omega^2 = 4 sin^2(k/2) / m / (s + sqrt(s^2 - 4 sin^2(k/2) / m)), s = 1 + 1/m (the
    small root without cancellation), differentiated twice in 50-digit arithmetic."""
    import mpmath

    mpmath.mp.dps = 50

    def omega(k):
        s2 = 4 * mpmath.sin(k / 2) ** 2 / m
        s = 1 + 1 / mpmath.mpf(m)
        return mpmath.sqrt(s2 / (s + mpmath.sqrt(s * s - s2)))

    return float(mpmath.diff(omega, mpmath.mpf(k), 2))


def test_the_smallest_k_the_nls_takes_gives_g1_its_true_sign():
    """A diatomic chain's acoustic omega^2 ~ k^2 is the small eigenvalue of an O(1)
    matrix, and g1 the difference of two O(1) terms: at k = 1e-4 its sign came out
    flipped ('stable'; the chain is MI there). Below the bound the NLS is refused; above
    it g1 has the 50-digit formula's sign, and its size once k is a few times the bound."""
    import re

    from energy import ModelError, load_model
    from numerics.models import nls

    model = load_model("diatomic-fput")
    with pytest.raises(ModelError, match=r"g1 .* cancel to within their rounding") as err:
        nls(model, 1e-4, 0)
    least = float(re.search(r">= (\S+)$", str(err.value)).group(1))
    # float64 resolves k^2 ~ 1e-7 differences of O(1) terms only from eps / k^2 < 1:
    # the bound is near sqrt(eps) ~ 1e-8 in k^2, k ~ 1e-4..1e-2
    assert 1e-4 < least < 1e-2
    for k in (1.01 * least, 10 * least, 0.3):
        assert np.sign(nls(model, k, 0).g1) == np.sign(_diatomic_g1(k)), k
    # 10x the bound: g1's rounding ~ 1/k^2 against its size ~ k, 1e-3 of the bound's
    assert nls(model, 10 * least, 0).g1 == pytest.approx(_diatomic_g1(10 * least), rel=1e-2)


def test_an_amplitude_whose_shift_is_lost_in_omega_is_refused_with_the_bound():
    """The bound is where the NLS's shift |g2| a^2/4 stops changing omega in float64:
    half of it is lost when added to omega, twice it is not."""
    import re

    from energy import ModelError
    from numerics.models import exact_gain, four_wave, nls

    r = nls(_fput(), 0.5)
    with pytest.raises(ModelError, match=r"amplitude a = 1e-300 is below what float64") \
            as err:
        r.peak_gain(1e-300)
    least = float(re.search(r">= (\S+)$", str(err.value)).group(1))
    omega, shift = r.carrier.omega, lambda a: abs(r.g2) * a * a / 4
    assert omega + shift(least / 2) == omega
    assert omega + shift(2 * least) != omega
    assert r.peak_gain(2 * least) > 0
    for theory in (lambda a: exact_gain(_fput(), 0.5, a, N=64),
                   lambda a: four_wave(_fput(), 0.5, a, N=64)):
        with pytest.raises(ModelError, match="below what float64 resolves"):
            theory(least / 2)


def test_point_refuses_a_tiny_amplitude_in_one_line(capsys):
    from cli.app import main

    code = main(["point", "--model", "fput", "--k", "0.5", "--amplitude", "1e-300"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1
    assert "--amplitude" in err[0] and "below what float64 resolves" in err[0]


def test_a_map_cell_of_a_tiny_amplitude_is_undefined_and_says_why():
    from numerics.models import map_cells

    row, = map_cells(_fput(), [({}, 0.5)], 1e-300)
    assert row["verdict_semidiscrete"] == "undefined"
    assert "below what float64 resolves" in row["reason"]


# --- a spectrum of another ring ------------------------------------------------------------

def test_simulate_seeds_refuses_a_spectrum_of_another_ring_at_the_same_k():
    """pi/4 is 2 pi 4/32 and 2 pi 8/64: k, amplitude, branch and model agree, yet the runs
    would start from the 64-site ring's wave with that ring's rates."""
    import math

    from energy import ModelError
    from numerics.models import exact_gain, simulate_seeds

    k = math.pi / 4
    for spec, said in ((exact_gain(_fput(), k, 0.05, N=64), "spec: N = 64"),
                       (exact_gain(_fput(), k, 0.05, samples=16), "spec: the infinite chain")):
        with pytest.raises(ModelError, match=rf"another wave: ring N = 32 \({said}"):
            simulate_seeds(_fput(), k, 0.05, spec, N=32, t_end=5.0)
    for N in (32, 33):  # the spectrum of the ring asked for runs, an odd ring's too
        spec = exact_gain(_fput(), k, 0.05, N=N)
        assert len(simulate_seeds(_fput(), k, 0.05, spec, N=N, t_end=5.0).runs) == 1


# --- a simulated model map's cells whose T is too short for their exact rate ---------------

def test_cells_whose_exact_rate_cannot_grow_20x_within_t_are_marked_and_counted():
    """ln 20 = 3.0: a rate 0.01 over T = 100 grows e^1 (too slow), over T = 1000 e^10; a
    cell the exact theory calls stable, or not simulated, is not 'too slow'."""
    params = _fput_map(N=64, t_end=100.0)
    arrays = {"done": np.array([[True, True], [True, False]]),
              "verdict_exact": np.array([[1, 1], [0, 1]], np.int8),
              "peak_gain_exact": np.array([[0.01, 0.01], [0.0, 0.01]]),
              "t_simulated": np.array([[100.0, 1000.0], [100.0, np.nan]]),
              "verdict_simulated": np.array([[0, 1], [0, -1]], np.int8)}
    dims, flag, attrs = params.derived_variables(arrays)["slow_for_T"]
    assert flag.tolist() == [[1, 0], [0, -1]]
    assert attrs["cells"] == 1 and attrs["runs_no_growth"] == 1
    assert params.derived_attrs({"slow_for_T": (dims, flag, attrs)})["slow_for_T_cells"] == 1
    assert "slow_for_T" not in _fput_map(theory_only=True, exact=True).derived_variables(
        arrays)


# --- a map's summary.json says what was run ------------------------------------------------

def test_a_paper_maps_summary_holds_its_inputs(tmp_path):
    import json

    from cli.app import main

    assert main(["map", "--alpha", "2.5", "--K-s", "0.01851", "--delta", "0.003,0.004",
                 "--k", "0.5,1.0", "--case", "rotation", "--theory-only", "--N", "64",
                 "--t-end", "700", "--workers", "1", "--out", str(tmp_path)]) == 0
    got = json.loads((tmp_path / "summary.json").read_text())["inputs"]
    assert got == {"command": "flexmm map", "case": "rotation", "alpha": 2.5,
                   "K_s": 0.01851, "axes": {"delta": [0.003, 0.004], "k": [0.5, 1.0]},
                   "k_simulated": got["k_simulated"], "amplitude": 0.02, "N": 64,
                   "t_end": 700.0, "seeds": got["seeds"], "start": "paper",
                   "theory_only": True, "device": "cpu", "block": got["block"]}
    # k as simulated: the ring's 2 pi m / 64 nearest each k
    assert got["k_simulated"] == pytest.approx([2 * np.pi * round(k * 64 / (2 * np.pi)) / 64
                                                for k in (0.5, 1.0)], rel=1e-12)


def test_a_model_maps_summary_holds_its_inputs(tmp_path):
    import json

    from cli.app import main

    assert main(["map", "--model", "fput", "--param", "alpha=1", "--param", "beta=0.8,1.6",
                 "--k", "2.6,2.8", "--amplitude", "0.1", "--theory-only", "--workers", "1",
                 "--out", str(tmp_path)]) == 0
    got = json.loads((tmp_path / "summary.json").read_text())["inputs"]
    assert got == {"command": "flexmm map --model", "model": "fput",
                   "parameters": {"alpha": 1.0}, "axes": {"beta": [0.8, 1.6], "k": [2.6, 2.8]},
                   "k": None, "amplitude": 0.1, "branch": None, "N": None, "t_end": None,
                   "seeds": None, "start": "exact", "exact": False, "theory_only": True,
                   "device": "cpu", "block": got["block"]}


def test_the_theory_columns_never_ask_distributed_for_a_client(tmp_path, monkeypatch):
    """A map store's theory columns run on Dask's threaded scheduler without the default
    client lookup, which races with the garbage collection of a closed client (CI saw
    'KeyError: 4' from distributed's _get_global_client while a damaged store's theory
    columns were recomputed). Here the registry's entry vanishes on every lookup."""
    pytest.importorskip("distributed")
    import distributed.client as dc

    from common import paper
    from numerics.maps import MapParameters, open_or_create

    class Vanishing(dict):
        def __getitem__(self, key):  # collected between list() and [key]
            raise KeyError(key)

    monkeypatch.setattr(dc, "_global_clients", Vanishing({4: None}))
    params = MapParameters(case="coupled", alpha=paper.ALPHA, K_s=paper.K_S,
                           delta=(0.0035, -0.002), k=(1.1, 1.6), amplitude=0.02, N=100,
                           t_end=300.0, theory_only=True, block=1)
    ds = open_or_create(tmp_path / "map.zarr", params, log=lambda *a: None)
    assert ds["verdict_exact"].shape == (2, 2)
