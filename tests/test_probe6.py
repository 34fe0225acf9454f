"""Fault probe 6 of the commands a user runs most (coefficients, point, soliton, map, with
and without --model) and of the model API: each test is a try that failed before its fix
(a silent nan, a traceback, a wrong answer or an advice that did not work)."""

from __future__ import annotations

import math

import numpy as np
import pytest


def _cli(capsys, *argv):
    from cli.app import main as cli

    code = cli(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_the_paper_chains_table_prints_no_nan_at_delta_zero(capsys):
    """delta = 0 (K_s = K_theta): g1 = 0, so g = g2/g1 is undefined; the table printed
    'nan' there while every other undefined cell prints '-' (the reason is below it)."""
    code, out, _ = _cli(capsys, "coefficients", "--alpha", "2.5", "--K-s", "0.02",
                        "--K-theta", "0.02", "--k", "1.3")
    assert code == 0
    assert "nan" not in out.lower() and "inf" not in out.lower()
    rows = [line for line in out.splitlines() if line.strip().startswith("g = g2/g1")]
    assert len(rows) == 2 and all(r.split()[-2:] == ["-", "-"] for r in rows)
    assert "undefined: g1 = 0" in out


@pytest.fixture(scope="module")
def fput():
    from energy import builtin, load_model

    return load_model(builtin("fput"))


@pytest.mark.parametrize("call, words", [
    (lambda fw, m: fw("fput", 1.0, 0.02), "model must be an energy.Model"),
    (lambda fw, m: fw(m, 1.0, 0.02, samples=1), "samples must be an integer >= 8"),
    (lambda fw, m: fw(m, 1.0, 0.02, samples=1.5), "samples must be an integer >= 8"),
    (lambda fw, m: fw(m, "1", 0.02), "k must be a real number in (0, pi]"),
])
def test_four_wave_refuses_what_exact_gain_refuses(call, words, fput):
    """four_wave('fput', ...) was an AttributeError ('str' object has no attribute 'code'),
    samples=1 answered on a grid of one offset (exact_gain refuses samples < 8) and
    samples=1.5 was a TypeError from numpy."""
    from energy import ModelError
    from numerics.models import four_wave

    with pytest.raises(ModelError) as exc:
        call(four_wave, fput)
    assert words in str(exc.value)


@pytest.mark.parametrize("method, args", [
    ("peak_gain", (float("nan"),)), ("peak_gain", (1e200,)), ("gain", (0.01, -1.0)),
    ("gain", (float("nan"), 0.02)), ("fastest_offset", (0.0,)), ("band_edge", (-1.0,)),
    ("frequency_shift", (math.inf,)), ("soliton", ("a",)),
])
def test_the_nls_refuses_a_bad_amplitude_or_offset(method, args, fput):
    """nls(...).peak_gain(nan) answered nan, peak_gain(1e200) raised OverflowError,
    gain(q, -1) a rate for a negative amplitude, band_edge(-1) a negative edge and
    soliton('a') numpy's 'could not convert string to float'."""
    from energy import ModelError
    from numerics.models import nls

    with pytest.raises(ModelError, match="amplitude must be|offset must be finite"):
        getattr(nls(fput, 1.0), method)(*args)


def test_the_nls_answers_at_good_amplitudes(fput):
    """The checks keep the answers: |g2| a^2 / 4, and the gain's peak at a sqrt(g / 2)."""
    from numerics.models import nls

    r, a = nls(fput, 1.0), 0.02
    assert r.peak_gain(a) == pytest.approx(abs(r.g2) * a**2 / 4, rel=1e-15)
    q = r.fastest_offset(a)
    assert r.gain(q, a) == pytest.approx(r.peak_gain(a), rel=1e-12)
    # at the edge sqrt(g a^2 - q^2) of a round-off difference: ~sqrt(1e-16) of the peak
    edge = r.gain(np.array([0.0, r.band_edge(a)]), a)
    assert edge == pytest.approx([0.0, 0.0], abs=1e-6 * r.peak_gain(a))


@pytest.mark.parametrize("change, words", [
    (dict(amplitude=0.5), "amplitude 0.5 (spec: 0.05)"),
    (dict(k=2.0), "k on the ring 1.9635 (spec: 0.981748)"),
    (dict(spec=None), "spec must be the exact theory"),
    (dict(t_end="5"), "t_end must be a finite time > 0"),
])
def test_simulate_seeds_refuses_a_spectrum_of_another_wave(change, words, fput):
    """simulate_seeds(model, k, a, spec) starts its runs from spec.wave: a spectrum of
    amplitude 0.05 with a = 0.5 asked ran 0.05 and reported it as 0.5's verdict; k = 2
    with a spectrum of k = 1 ran k = 1 (growth 1.0000000008, 'no growth'); spec=None was
    an AttributeError and t_end='5' was taken as 5."""
    from energy import ModelError
    from numerics.models import exact_gain, simulate_seeds

    spec = exact_gain(fput, 1.0, 0.05, N=32)
    kw = dict(k=1.0, amplitude=0.05, spec=spec, N=32, t_end=5.0) | change
    with pytest.raises(ModelError) as exc:
        simulate_seeds(fput, kw.pop("k"), kw.pop("amplitude"), kw.pop("spec"), **kw)
    assert words in str(exc.value)
    # the matching call runs (the check refuses only another wave)
    ok = simulate_seeds(fput, 1.0, 0.05, spec, N=32, t_end=5.0)
    assert ok.t_end == 5.0 and len(ok.runs) == 1


def test_a_map_json_gives_no_default_for_a_swept_parameter(capsys, tmp_path):
    """map --model fput --param beta=0.5,1.5 --json printed "parameters": {"alpha": 0,
    "beta": 1.0}: the file's default for the axis it swept, read as the map's beta."""
    import json

    code, out, _ = _cli(capsys, "map", "--model", "fput", "--param", "beta=0.5,1.5",
                        "--k", "1,2", "--theory-only", "--N", "32", "--workers", "1",
                        "--json", "--out", str(tmp_path / "m"))
    assert code == 0
    res = json.loads(out)
    assert res["parameters"] == {"alpha": 0.0}
    assert res["axes"]["beta"] == [0.5, 1.5]


def test_a_model_maps_axes_say_what_they_are(capsys, tmp_path):
    """The store's parameter and amplitude axes had no attributes (k had its unit only),
    where every variable says its unit."""
    import xarray as xr

    for axes in (["--param", "beta=0.5,1.5", "--k", "1,2"],
                 ["--amplitude", "0.01,0.02", "--param", "beta=0.5,1.5", "--k", "1"]):
        out = tmp_path / axes[0].strip("-")
        code, _, _ = _cli(capsys, "map", "--model", "fput", *axes, "--theory-only",
                          "--workers", "1", "--out", str(out))
        assert code == 0
        with xr.open_zarr(out / "map.zarr") as ds:
            for name in ds.dims:
                assert {"long_name", "units"} <= set(ds[name].attrs), name


def _advised_N(text: str) -> int:
    import re

    found = re.findall(r"--N (\d+) holds", text)
    assert len(found) == 1, text
    return int(found[0])


def test_a_models_soliton_ring_advice_is_a_ring_that_holds_it(capsys, fput):
    """soliton --model fput --k 1 --simulate --N 16 advised 'N >= 12 widths = 4409' (12
    widths at the 16-site ring's k = 1.178); --N 4410 was then refused for 5109 (its k is
    near 1, where the soliton is wider). The advice now names a ring that holds it."""
    from numerics.models import ring_soliton

    code, _, err = _cli(capsys, "soliton", "--model", "fput", "--k", "1", "--simulate",
                        "--N", "16")
    assert code == 2 and err.startswith("flexmm: error: --N 16 is too short")
    N = _advised_N(err)
    ring = ring_soliton(fput, 1.0, 0.002, N=N)  # the default amplitude of the command
    assert 12 * ring.soliton.width <= N
    # the old advice (12 widths at the short ring's k) is refused: the advice is not it
    old = int(err.split("(12 widths = ")[1].split()[0])
    assert old < N


def test_the_paper_chains_soliton_ring_advice_names_the_option_and_holds_it(capsys, blue):
    """soliton --simulate --N 16 at the blue point, case coupled: the ring's k (0.98) has
    the other kind, and the error said "kind='dark': ..." (no --kind was given; --N and a
    remedy unnamed); a short ring said 'N = 64 is too short' with the API's name and the
    short ring's width."""
    from numerics.theory import simulate_soliton

    args = ["soliton", "--alpha", "2.5", "--K-s", "0.01851", "--K-theta", "0.01551",
            "--k", "0.81681", "--case", "coupled", "--simulate"]
    code, _, err = _cli(capsys, *args, "--N", "16")
    assert code == 2 and err.startswith("flexmm: error: --N 16 moves k to 0.981748")
    assert "kind=" not in err
    code, _, err64 = _cli(capsys, *args, "--N", "64")
    assert code == 2 and err64.startswith("flexmm: error: --N 64 is too short")
    for text in (err, err64):
        N = _advised_N(text)
        run = simulate_soliton(blue, "coupled", 0.81681, 0.002, N=N, t_end=1.0, snapshots=2)
        assert run.N == N and 12 * run.predicted.width <= N


@pytest.mark.parametrize("extra", [["--exact", "--theory-only"], ["--t-end", "50"]])
def test_a_model_map_says_two_k_are_one_ring_wavenumber(extra, capsys, tmp_path):
    """--k 1,1.01 on N = 32 (both 2 pi 5 / 32): the model map ran both columns, identical
    cells under two k labels, without a word (the paper chain's map refuses them; a model
    map keeps them, and says so)."""
    code, out, _ = _cli(capsys, "map", "--model", "fput", "--param", "beta=0.5,1", "--k",
                        "1.01,2,1", "--N", "32", "--workers", "1", "--out",
                        str(tmp_path / "m"), *extra)
    assert code == 0
    assert ("note: --k 1 and 1.01 both snap to 2 pi 5/32 = 0.981748 on the ring of N = 32: "
            "their columns are one carrier, computed twice; a larger --N separates them") in out


def test_a_theory_only_model_map_keeps_close_k_values_unnoted():
    """Without a ring (the semi-discrete NLS alone) close k values are distinct carriers."""
    from numerics.maps import ModelMapParameters

    p = ModelMapParameters.from_model("fput", ("beta", [0.5, 1.0]), ("k", [1.0, 1.01]), 0.02,
                                      theory_only=True, N=32)
    assert p.grid_shape == (2, 2) and p.same_ring_k() is None
    q = ModelMapParameters.from_model("fput", ("beta", [0.5, 1.0]), ("k", [1.0, 1.01]), 0.02,
                                      theory_only=True, exact=True, N=32)
    assert "both snap to 2 pi 5/32" in q.same_ring_k()


@pytest.mark.parametrize("name, branch", [("fput", 0), ("klein-gordon", 0),
                                          ("diatomic-fput", 0), ("diatomic-fput", 1)])
def test_the_group_velocity_at_the_zone_boundary_is_zero(name, branch, capsys):
    """omega(pi + q) = omega(pi - q): v_g(pi) = 0. It was sin(pi)'s round-off, printed as
    'group velocity 6.12323e-17' and a soliton's 'velocity 6.123e-17 sites/time'. A
    one-sided difference agrees: (omega(pi) - omega(pi - h)) / h = -g1 h / 2 + O(h^2)."""
    from energy import builtin, load_model
    from numerics.models import carrier

    model = load_model(builtin(name))
    c = carrier(model, math.pi, branch)
    assert c.group_velocity == 0.0
    h = 1e-4
    slope = (c.omega - carrier(model, math.pi - h, branch).omega) / h
    assert slope == pytest.approx(-c.g1 * h / 2, rel=1e-3)  # O(h) relative: 1e-4, and slack
    code, out, _ = _cli(capsys, "soliton", "--model", name, "--k", repr(math.pi),
                        "--branch", str(branch))
    assert code in (0, 2)  # a branch may have no soliton there; the velocity is the point
    if code == 0:
        assert "velocity 0 sites/time" in out


def test_a_model_map_says_where_k_snapped(capsys, tmp_path):
    """--k pi on a ring of 33 sites is 2 pi 16 / 33 = 3.046: the model map ran it without
    a word (the paper chain's map says 'k values snapped'); a k the ring carries is not
    named."""
    code, out, _ = _cli(capsys, "map", "--model", "fput", "--param", "beta=1,2", "--k",
                        f"{math.pi!r},2", "--theory-only", "--exact", "--N", "33",
                        "--workers", "1", "--out", str(tmp_path / "a"))
    assert code == 0
    assert "note: 2 of 2 k values snapped to 2 pi m / N (N = 33), e.g. 2 -> 2.0944" in out
    code, out, _ = _cli(capsys, "map", "--model", "fput", "--param", "beta=1,2", "--k",
                        f"{math.pi!r},{2 * math.pi * 5 / 32!r}", "--theory-only", "--exact",
                        "--N", "32", "--workers", "1", "--out", str(tmp_path / "b"))
    assert code == 0 and "snapped" not in out


@pytest.mark.parametrize("change, error, words", [
    (dict(rows="beta"), TypeError, "rows must be (axis name, values)"),
    (dict(rows=("beta", [1.0, 1.0])), ValueError, "rows (beta) repeats a value"),
    (dict(branch="5"), ValueError, "branch must be in 0..0 for model 'fput'"),
    (dict(branch=5), ValueError, "branch must be in 0..0 for model 'fput'"),
    (dict(branch="x"), ValueError, "neither an index nor a field"),
    (dict(branch=1.0), TypeError, "branch must be an index or a field name"),
])
def test_model_map_parameters_refuse_in_one_line(change, error, words):
    """rows='beta' was 'too many values to unpack'; a repeated value ran one cell twice;
    branch='5' (or 'x') made every cell undetermined without a word (run_map returned a
    map of -1), and branch=1 (an int) an AttributeError once the store was named."""
    from numerics.maps import ModelMapParameters

    kw = dict(rows=("beta", [1.0, 2.0]), cols=("k", [1.0, 2.0]), theory_only=True) | change
    with pytest.raises(error) as exc:
        ModelMapParameters.from_model("fput", kw.pop("rows"), kw.pop("cols"), 0.02, **kw)
    assert words in str(exc.value)


def test_a_model_maps_branch_index_is_kept_as_the_cli_gives_it():
    from numerics.maps import ModelMapParameters

    p = ModelMapParameters.from_model("diatomic-fput", ("m", [1.5, 2.0]), ("k", [1.0, 2.0]),
                                      0.02, theory_only=True, branch=1)
    assert p.branch == "1" and p.branch_value == 1


@pytest.mark.parametrize("kw, error, words", [
    (dict(workers=0), ValueError, "workers must be an integer >= 1"),
    (dict(workers=1, timeout=-1.0), ValueError, "timeout must be a finite time > 0"),
    (dict(workers=1, timeout=float("nan")), ValueError, "timeout must be a finite time > 0"),
])
def test_run_map_refuses_bad_options_before_any_work(kw, error, words, tmp_path):
    """workers=0 ran as the default workers; timeout=-1 (with a scheduler) was the socket
    module's 'Timeout value out of range'; an out that is a file was FileExistsError."""
    from numerics.maps import ModelMapParameters, run_map

    p = ModelMapParameters.from_model("fput", ("beta", [1.0, 2.0]), ("k", [1.0, 2.0]), 0.02,
                                      theory_only=True)
    with pytest.raises(error, match=words):
        run_map(p, tmp_path / "m", scheduler="tcp://127.0.0.1:1", **kw)
    assert not (tmp_path / "m").exists()
    (tmp_path / "f").write_text("x")
    with pytest.raises(ValueError, match="is a file, not a folder"):
        run_map(p, tmp_path / "f", workers=1)
    with pytest.raises(TypeError, match="out must be a folder"):
        run_map(p, None, workers=1)


def test_soliton_physical_answers_in_seconds_and_metres(capsys, tmp_path):
    """--physical promises answers 'also in seconds and metres' (its help): coefficients
    and point gave them, soliton printed lattice units only and dropped the units line."""
    import json

    m, J, a, k_l = 1e-3, 1e-7, 0.01, 100.0
    T = math.sqrt(m / k_l)  # seconds per lattice time unit (below eq. norm)
    code, out, _ = _cli(capsys, "soliton", "--physical", f"{m},{J},{a},{k_l},2,0.001",
                        "--k", "1", "--case", "rotation", "--out", str(tmp_path))
    assert code == 0
    assert f"1 T = sqrt(m/k_l) = {T:.4g} s, 1 site = a = {a:.4g} m" in out
    res = json.loads((tmp_path / "soliton.json").read_text())
    pred, si = res["predicted"], res["si"]["predicted"]
    assert si["width"] == pytest.approx(pred["width"] * a, rel=1e-12)
    assert si["velocity"] == pytest.approx(pred["velocity"] * a / T, rel=1e-12)
    assert si["frequency"] == pytest.approx(pred["frequency"] / T, rel=1e-12)
    assert f"width {si['width']:.4g} m" in out and f"{si['velocity']:.4g} m/s" in out


def test_a_lossy_models_soliton_says_it_decays(capsys):
    """soliton --model flexmm-lossy printed a soliton's width, velocity and frequency as
    if it lasted, losses unsaid (--simulate refuses a lossy model; the prediction did not
    say why it cannot hold)."""
    import json

    from energy import builtin, load_model
    from numerics.models import carrier_damping

    model = load_model(builtin("flexmm-lossy"))
    gamma = carrier_damping(model, 1.0)
    assert gamma > 0
    code, out, _ = _cli(capsys, "soliton", "--model", "flexmm-lossy", "--k", "1")
    assert code == 0
    assert f"the carrier's amplitude decays at {gamma:.4g} /time (e-folding " \
           f"{1 / gamma:.4g} time)" in out
    code, out, _ = _cli(capsys, "soliton", "--model", "flexmm-lossy", "--k", "1", "--json")
    assert code == 0 and json.loads(out)["carrier_damping"] == pytest.approx(gamma, rel=1e-12)
    code, out, _ = _cli(capsys, "soliton", "--model", "flexmm-lossy", "--k", "1", "--param",
                        "gamma_theta=0", "--param", "gamma_U=0")
    assert code == 0 and "dissipation" not in out


@pytest.mark.parametrize("k", [4.0, -1.0, 0.0, float("nan"), "1", True])
def test_the_infinite_chains_exact_theory_refuses_a_k_outside_the_zone(k):
    """exact_gain without N took k = 4 (a peak gain of 9e-4) or -1 and answered, where the
    ring path, nls and four_wave refuse k outside (0, pi]."""
    from energy import ModelError, load_model
    from numerics.models import exact_gain

    with pytest.raises(ModelError, match=r"k must be .*\(0, pi\]"):
        exact_gain(load_model("fput"), k, 0.1)
