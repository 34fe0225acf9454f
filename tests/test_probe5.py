"""Fault probe 5 of the model path (`--model FILE.toml`): each test is a try that failed
before its fix (a traceback, a hang, a vague error or a wrong word)."""

from __future__ import annotations

import math
import time

import numpy as np
import pytest


def _wrap(x):
    return -((-x + math.pi) % (2 * math.pi) - math.pi)


def _copies_by_scan(q, g, k, step):
    """The copy rule of ``numerics.maps._model_point_curves.hill_copies`` as a plain scan of every kept
    offset (its form before the binned look-up): the reference the fast form must equal."""
    grows = g > 0
    edges = np.flatnonzero(np.diff(np.concatenate([[0], grows.astype(int), [0]])))
    kept, copy_of, g = [], [], g.copy()
    for a, b in zip(edges[::2], edges[1::2]):
        for i in range(a, b):
            match = next((j for j in kept if abs(g[i] - g[j]) <= 0.02 * max(g[i], g[j])
                          and any(abs(_wrap(q[i] - s * q[j] - ell * k)) <= step / 2
                                  for s in (1, -1) for ell in range(-3, 4))), None)
            if match is None:
                kept.append(i)
            else:
                copy_of.append((float(q[i]), float(q[match])))
                g[match] = max(g[match], g[i])
    return sorted(copy_of), g


@pytest.mark.parametrize("N, m", [(64, 25), (96, 17), (250, 81)])
def test_hill_copies_equal_the_plain_scan(N, m):
    """The binned look-up finds the copies the quadratic scan finds, on ring offsets with
    bands that repeat one another at +-q + l k (and gains that do or do not agree)."""
    from numerics.maps._model_point_curves import hill_copies

    rng = np.random.default_rng(N)
    q = 2 * np.pi * np.arange(1, N // 2 + 1) / N
    k = 2 * np.pi * m / N
    g = np.where(rng.random(q.size) < 0.5, 0.0, 0.01)  # ties: copies agree to 2%
    g[rng.random(q.size) < 0.3] *= 1.5  # some do not
    ref, ref_g = _copies_by_scan(q, g, k, float(np.min(np.diff(q))))
    got = hill_copies(q, g, k)
    assert [tuple(c) for c in got["copy_of"]] == ref
    assert np.array_equal(got["gain"], ref_g)


def test_hill_copies_of_a_large_ring_is_fast():
    """A ring of 2^20 sites (the largest --N) with a band of 30 000 unstable offsets: the
    point's curve took hours (a scan of every kept offset per offset); now well under a
    minute on a shared 2-core machine (measured ~1 s here; 30 s allows a 30x slower box)."""
    from numerics.maps._model_point_curves import hill_copies

    N = 2**20
    q = 2 * np.pi * np.arange(1, N // 2 + 1) / N
    g = np.where(q < 0.18, 0.001 * np.sin(q / 0.18 * np.pi) + 1e-4, 0.0)
    t = time.perf_counter()
    out = hill_copies(q, g, 2 * np.pi * 160_000 / N)
    assert time.perf_counter() - t < 30
    assert out["gain"].max() == g.max()


def _cli(capsys, *argv):
    from cli.app import main as cli

    code = cli(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("argv", [
    ["coefficients", "--model", "fput", "--k", "1"],
    ["point", "--model", "fput", "--k", "1", "--N", "32"],
    ["soliton", "--model", "fput", "--k", "2"],
    ["map", "--model", "fput", "--param", "beta=1,2", "--k", "1,2", "--theory-only"],
])
def test_a_huge_amplitude_is_refused_in_one_line(argv, capsys, tmp_path):
    """--amplitude 1e200 overflowed the NLS's gain (a**2): an OverflowError traceback in
    all four commands. Now one line naming --amplitude, exit 2, nothing written."""
    out = ["--out", str(tmp_path / "m")] if argv[0] == "map" else []
    code, _, err = _cli(capsys, *argv, *out, "--amplitude", "1e200")
    assert code == 2
    assert err.startswith("flexmm: error: --amplitude must be") and "1e+15" in err
    assert err.count("\n") == 1
    assert not (tmp_path / "m").exists()


def test_a_map_amplitude_axis_beyond_the_bound_is_refused(capsys, tmp_path):
    code, _, err = _cli(capsys, "map", "--model", "fput", "--amplitude", "1e100,1e200",
                        "--k", "1,2", "--theory-only", "--out", str(tmp_path / "m"))
    assert code == 2 and "--amplitude must be at most 1e+15" in err


def test_a_huge_parameter_is_refused_naming_it(capsys):
    """--param alpha=1e100: g2 overflowed and --json died on 'Out of range float values
    are not JSON compliant' (no option named)."""
    code, _, err = _cli(capsys, "coefficients", "--model", "fput", "--k", "1",
                        "--amplitude", "0.1", "--param", "alpha=1e100", "--json")
    assert code == 2
    # the CLI names the option the value came from (the library says "parameter alpha")
    assert "--param alpha=1e+100: must be at most 1e+15" in err and err.count("\n") == 1


def test_json_of_an_undefined_four_wave_row_is_strict(capsys):
    """At the bound (alpha = 1e15) the four-wave theory is undefined and its frequency nan:
    the JSON writes null (as every undefined number), the text says why."""
    import json

    code, out, _ = _cli(capsys, "coefficients", "--model", "fput", "--k", "1",
                        "--amplitude", "0.1", "--param", "alpha=1e15", "--json")
    assert code == 0
    fw = json.loads(out)["four_wave"]
    assert fw["verdict"] == "undefined" and fw["frequency"] is None and fw["reason"]
    code, out, _ = _cli(capsys, "coefficients", "--model", "fput", "--k", "1",
                        "--amplitude", "0.1", "--param", "alpha=1e15")
    assert code == 0 and "four-wave undefined: " in out
    # the shift is 1.2e28 omega: said as a factor, not as a 30-digit percentage
    assert "times omega" in out and "%" not in out.split("note:")[1]


def test_a_linear_chain_has_no_soliton_and_no_focusing_word(capsys):
    """FPUT at alpha = beta = 0 is linear: g2 = 0. soliton divided by sqrt|g| = 0 (a
    ZeroDivisionError traceback) and coefficients called it 'stable (defocusing)', g -0."""
    for extra in ([], ["--simulate"]):
        code, _, err = _cli(capsys, "soliton", "--model", "fput", "--param", "beta=0",
                            "--k", "1", "--amplitude", "0.1", *extra)
        assert code == 2 and "no soliton: g2 = 0" in err, err
    code, out, _ = _cli(capsys, "coefficients", "--model", "fput", "--param", "beta=0",
                        "--k", "1", "--amplitude", "0.1")
    assert code == 0
    assert "stable (g2 = 0)" in out and "defocusing" not in out
    g_line = next(line for line in out.splitlines() if line.startswith("g = g2/g1"))
    assert g_line.split()[-1] == "0"


@pytest.mark.parametrize("option, value", [("--t-end", "-1"), ("--t-end", "1e30"),
                                           ("--seeds", "0"), ("--seeds", "5000")])
def test_point_checks_its_runs_options_before_any_theory(option, value, capsys):
    """point --model --simulate checked --seeds after the theories and an estimate of '0
    run(s)'; --t-end -1 was refused as 't_end ... got -0.0001' (the estimate's probe), and
    --t-end 1e30 hung in that probe with no output. Now each is refused at once, named,
    with the paper chain point's bounds."""
    t = time.perf_counter()
    code, out, err = _cli(capsys, "point", "--model", "fput", "--k", "1", "--amplitude",
                          "0.1", "--N", "32", "--simulate", option, value)
    assert code == 2 and err.startswith(f"flexmm: error: {option} must be")
    assert "estimate" not in out + err and "point:" not in out + err
    assert time.perf_counter() - t < 20  # refused before anything runs (~0.1 s here)


def test_a_store_of_another_amplitude_names_what_differs(capsys, tmp_path):
    """The same map run again at another amplitude was refused as 'a map of model 'fput'
    with other parameters', parameters that were the same: the refusal names the
    amplitude, the stored value and the asked one."""
    argv = ["map", "--model", "fput", "--param", "beta=1,2", "--k", "1,2", "--theory-only",
            "--out", str(tmp_path / "m")]
    assert _cli(capsys, *argv, "--amplitude", "0.1")[0] == 0
    code, _, err = _cli(capsys, *argv, "--amplitude", "0.2")
    assert code == 2 and "(amplitude 0.1 stored, 0.2 asked)" in err, err
    code, _, err = _cli(capsys, *argv, "--amplitude", "0.1", "--param", "alpha=0.5")
    assert code == 2 and "(alpha 0.0 stored, 0.5 asked)" in err, err


def _api_cases():
    import numerics.models as nm
    from energy import load_model

    m = load_model("fput")
    wave = nm.travelling_wave(m, 1.0, 0.1)
    return [
        # (call, words the one-line error holds): each raised an AttributeError, an
        # OverflowError, a TypeError from inside, or passed a wrong type through
        (lambda: nm.nls("fput", 1.0), "model must be an energy.Model"),
        (lambda: nm.carrier(m, [1, 2]), "k must be a finite real number"),
        (lambda: nm.model_coefficients(m, 1.0, "0.1"), "amplitude must be a real number"),
        (lambda: nm.model_coefficients(m, 1.0, None), "amplitude must be a real number"),
        (lambda: nm.model_coefficients(m, 1.0, 1e200), "at most 1e+15"),
        (lambda: nm.travelling_wave(m, 1.0, True), "amplitude must be a real number"),
        (lambda: nm.hill_spectrum(None, [0.1]), "wave must be a TravellingWave"),
        (lambda: nm.hill_spectrum(wave, [math.nan]), "offsets must be finite"),
        (lambda: nm.energy_not_real(m, 1.0, "x"), "amplitude must be a real number"),
        (lambda: nm.simulate_model(m, 1.0, 0.1, N=16, t_end="5"), "t_end must be"),
        (lambda: nm.model_map(m, "beta", ("k", [1.0, 2.0]), 0.1), "(name, values) pair"),
    ]


@pytest.mark.parametrize("case", range(11))
def test_the_model_api_refuses_wrong_types_in_one_line(case):
    from energy import ModelError

    call, words = _api_cases()[case]
    with pytest.raises(ModelError) as exc:
        call()
    assert words in str(exc.value) and "\n" not in str(exc.value)


def test_a_stiff_model_run_is_refused_not_hung(capsys):
    """diatomic-fput at m = 1e-300: its optical branch sits at 1.6e150, the step at 4e-151;
    point --simulate hung (no output past 150 s) in the estimate's probe run. Now the run
    is refused in one line naming the frequency and the step."""
    t = time.perf_counter()
    code, _, err = _cli(capsys, "point", "--model", "diatomic-fput", "--param", "m=1e-300",
                        "--k", "1", "--N", "32", "--amplitude", "0.05", "--simulate",
                        "--seeds", "1")
    assert code == 2 and "highest frequency 1.56e+150" in err and "steps" in err
    assert time.perf_counter() - t < 60  # ~1 s here; it never ended before


def test_an_overflowing_coupling_warns_nothing(capsys, recwarn):
    """The same model's four-wave kernel overflowed (C12 C21 / 4 w1 w2 at 1e150) and
    printed numpy's RuntimeWarning among the results; the pair is no rate (nan) either way."""
    code, out, err = _cli(capsys, "coefficients", "--model", "diatomic-fput", "--param",
                          "m=1e-300", "--k", "1", "--branch", "1", "--amplitude", "0.05")
    assert code == 0 and "RuntimeWarning" not in err
    assert not [w for w in recwarn if issubclass(w.category, RuntimeWarning)]


@pytest.mark.parametrize("argv", [
    ["coefficients", "--model", "fput", "--k", "1", "--branch", "1"],
    ["point", "--model", "diatomic-fput", "--k", "1", "--N", "32", "--branch", "w"],
    ["soliton", "--model", "diatomic-fput", "--k", "1", "--branch", "1.5"],
    ["map", "--model", "diatomic-fput", "--param", "m=1,2", "--k", "1,2", "--branch", "-1",
     "--theory-only"],
])
def test_a_bad_branch_is_named_as_the_option(argv, capsys, tmp_path):
    """'branch must be in 0..0 for model ...' or 'branch 'w' is neither ...' did not name
    --branch (and a map said it after starting its cluster)."""
    out = ["--out", str(tmp_path / "m")] if argv[0] == "map" else []
    code, _, err = _cli(capsys, *argv, *out)
    assert code == 2 and err.startswith("flexmm: error: --branch ") and "give an index" in err
    assert not (tmp_path / "m").exists()


def test_a_unicode_name_is_refused_saying_ascii(tmp_path):
    from energy import ModelError, parse_model

    text = ('name = "x"\nfields = ["\\u03b8"]\n[energy]\nkinetic = "\\u03b8_t**2/2"\n'
            'bond = "(\\u03b8_next - \\u03b8)**2/2"\n')
    with pytest.raises(ModelError, match="ASCII letters.*'theta' for"):
        parse_model(text)


def test_a_model_map_says_how_many_cells_are_undetermined(capsys, tmp_path):
    """A k axis through Klein-Gordon's inflection point (g1 = 0: no NLS there, cos k =
    (3 - sqrt 5) / 2): 'MI share, semidiscrete: 50%' read as half the cells stable; the
    text now counts the undetermined cells (the JSON and summary.json by theory name), and
    the share is of the cells the theory decides (the paper map's definition): the two
    cells at k = 2 are both MI (the 50% of all four cells it printed before)."""
    import json

    k0 = math.acos((3 - math.sqrt(5)) / 2)  # omega^2 = 3 - 2 cos k: omega'' = 0 there
    argv = ["map", "--model", "klein-gordon", "--param", "beta=1,2", "--k", f"2,{k0!r}",
            "--amplitude", "0.1", "--theory-only", "--out", str(tmp_path / "m")]
    code, out, _ = _cli(capsys, *argv)
    assert code == 0
    assert "MI share, semidiscrete: 100% (2 of 4 cells undetermined, left out)" in out
    code, out, _ = _cli(capsys, *argv, "--json")
    assert code == 0 and json.loads(out)["undetermined_cells"] == {"semidiscrete": 2}


def test_a_wavenumber_no_ring_carries_gives_a_possible_remedy(capsys):
    """k = 1e-9 on 64 sites said 'raise N above 3141592654', past the largest ring."""
    code, _, err = _cli(capsys, "point", "--model", "fput", "--k", "1e-9", "--N", "64")
    assert code == 2 and "no ring carries it (N at most 1048576)" in err
    code, _, err = _cli(capsys, "point", "--model", "fput", "--k", "0.01", "--N", "64")
    assert code == 2 and "raise N above 315" in err


def test_an_amplitude_in_a_field_that_hardly_moves_is_said(capsys):
    """diatomic-fput's acoustic branch at k = 3.14 is nearly all v (u moves 0.0016 of it):
    a = 0.1 of u is v = 63, and the output said only that the shift was 147 839% of
    omega. The note names the fields, v's amplitude and the --branch that measures v."""
    import json

    code, out, _ = _cli(capsys, "coefficients", "--model", "diatomic-fput", "--k", "3.14",
                        "--amplitude", "0.1", "--branch", "0", "--json")
    co = json.loads(out)
    e = co["amplitude"] / 0.0016  # the ratio the note states, to its 2 digits
    note = next(w for w in co["warnings"] if "hardly" in w or "moves" in w)
    assert "field u moves 0.0016 of v" in note and "--branch v" in note
    v = float(note.split(" is v = ")[1].split(";")[0])
    assert abs(v / e - 1) < 0.05  # 0.0016 is rounded to 2 digits
    code, out, _ = _cli(capsys, "coefficients", "--model", "diatomic-fput", "--k", "1",
                        "--amplitude", "0.1", "--json")
    assert not [w for w in json.loads(out)["warnings"] if "moves" in w]


def test_no_wave_where_the_energy_is_not_real_says_so(tmp_path):
    """A site energy u^2/2 - log(1 + u) + u (real for u > -1) at amplitude 3: the exact
    theory said the wave's family 'folds' (a resonance), the energy's edge unsaid; now it
    names the largest amplitude the energy allows (about 1)."""
    from energy import ModelError, load_model, parse_model
    from numerics.models import exact_gain_checked

    text = ('name = "logsite"\nfields = ["u"]\n[energy]\nkinetic = "u_t**2/2"\n'
            'bond = "(u_next - u)**2/2"\nsite = "u**2/2 - log(1 + u) + u"\n')
    model = load_model(parse_model(text))
    with pytest.raises(ModelError, match="energy is not real.*allows at k = 1 is about 1 "):
        exact_gain_checked(model, 1.0, 3.0, N=16)


@pytest.mark.parametrize("extra, start", [
    (["--k", "1", "--N", "16"], "flexmm: error: --N 16 is too short"),
    (["--k", "2.5", "--kind", "dark"], "flexmm: error: --kind dark: the NLS"),
])
def test_soliton_simulate_names_its_options(extra, start, capsys):
    """soliton --model --simulate said 'N = 16 is too short' and 'kind dark: ...' (the
    API's names) where the command without --simulate says '--kind dark: ...'."""
    code, _, err = _cli(capsys, "soliton", "--model", "fput", "--amplitude", "0.05",
                        "--simulate", "--travel", "2", *extra)
    assert code == 2 and err.startswith(start), err


def test_a_map_cell_on_the_ring_answers_as_point(capsys, tmp_path):
    """map --model --exact put the NLS at the asked k (2) and the exact theory at the
    ring's (1.9635): its peak_gain_semidiscrete, 0.01787, contradicted point's 0.01724 at
    the same cell. Now every theory of a ring cell is at the ring's k."""
    import json

    import xarray as xr

    argv = ["--model", "fput", "--k", "2", "--amplitude", "0.1", "--N", "32"]
    code, out, _ = _cli(capsys, "point", *argv, "--param", "beta=1", "--json")
    point = json.loads(out)
    code, _, _ = _cli(capsys, "map", *argv[:2], "--k", "1,2", "--amplitude", "0.1", "--N",
                      "32", "--param", "beta=0.5,1", "--theory-only", "--exact", "--out",
                      str(tmp_path / "m"))
    assert code == 0
    ds = xr.open_zarr(tmp_path / "m" / "map.zarr")
    cell = ds.sel(beta=1.0, k=2.0)
    for col, row in (("semidiscrete", "semi-discrete NLS"), ("exact", "exact lattice"),
                     ("fourwave", "four-wave")):
        # the same functions at the same k and ring: equal to rounding
        assert float(cell[f"peak_gain_{col}"]) == pytest.approx(point[row]["peak_gain"],
                                                               rel=1e-9), col


def test_a_ring_whose_modes_are_all_the_carriers_claims_no_stability(capsys):
    """FPUT at k = 8 pi / 9 on 9 sites: the sidebands k +- 2 pi / 9 are -k and 3k, every
    ring mode a harmonic of the carrier. The run's deviation from the wave grows 1e8x (the
    exact theory's rate 0.187), yet the run read 'no growth within T' (nothing left to
    measure: factor 0). Now it is undetermined, and point says why."""
    from energy import load_model
    from numerics.models import simulate_model

    run = simulate_model(load_model("fput"), 3.1, 0.3, N=9, t_end=120)
    assert run.deviation[-1] > 1e6 * run.deviation[0]  # it grows: the physics
    g = run.growth()
    assert g.verdict == "undetermined" and math.isnan(g.factor)
    code, out, _ = _cli(capsys, "point", "--model", "fput", "--k", "3.1", "--amplitude",
                        "0.3", "--N", "9", "--simulate", "--seeds", "1")
    assert code == 0 and "no growth within T" not in out
    assert "every mode of the ring is a harmonic of the carrier" in out


@pytest.mark.parametrize("name, params, branch", [
    ("fput", {"alpha": 0.5}, None), ("fput", {"alpha": 1.0}, None),
    ("diatomic-fput", {"alpha": 0.3}, 1), ("flexmm", {}, None),
    ("klein-gordon", {"alpha": 0.5}, None), ("sine-gordon", {}, None)])
def test_the_nls_at_the_zone_boundary_is_its_limit(name, params, branch):
    """k = pi was refused by the NLS (point: 'undefined ... 2k is the mean') while
    k = pi - 1e-9 answered and the exact theory and runs take pi. Its 2k harmonic is
    uniform at 2 omega, apart from the mean: the coefficients at pi are the limit."""
    from energy import load_model
    from numerics.models import nls

    m = load_model(name, **params)
    at, near = nls(m, math.pi, branch), nls(m, math.pi - 1e-7, branch)
    assert not at.undefined
    # the coefficients are even in k - pi: 1e-7 away they differ by ~1e-14 relative
    assert at.g2 == pytest.approx(near.g2, rel=1e-9)
    assert at.g1 == pytest.approx(near.g1, rel=1e-9)


@pytest.mark.parametrize("alpha, beta, word", [(0.5, 1.0, "MI"), (1.0, 1.0, "stable"),
                                               (1.0, 1.4, "MI"), (1.0, 1.3, "stable")])
def test_fput_at_the_zone_boundary_follows_3_beta_above_4_alpha_squared(alpha, beta, word,
                                                                        capsys):
    """MI of FPUT's zone-boundary mode iff 3 beta > 4 alpha^2 (Flach & Gorbach, Phys.
    Rep. 467 (2008)): the criterion from the literature, not from this code."""
    import json

    code, out, _ = _cli(capsys, "coefficients", "--model", "fput", "--param",
                        f"alpha={alpha}", "--param", f"beta={beta}", "--k",
                        repr(math.pi), "--amplitude", "0.05", "--json")
    assert code == 0 and json.loads(out)["verdict"] == word


def test_a_standing_soliton_at_the_zone_boundary_is_refused_with_a_k_that_runs(capsys):
    """soliton --simulate at k = 3.13 on 256 sites (the ring's nearest is pi, v_g = 0):
    'no ring wavenumber near k' gave no reason nor remedy; now it says why and the
    largest k that runs, and that k runs."""
    argv = ["soliton", "--model", "fput", "--param", "alpha=0.5", "--amplitude", "0.05",
            "--simulate", "--travel", "2"]
    code, _, err = _cli(capsys, *argv, "--k", "3.13")
    assert code == 2 and "v_g = 0" in err
    k = err.split("k <= ")[1].split(" ")[0]
    assert _cli(capsys, *argv, "--k", k)[0] == 0


def test_a_model_file_with_a_byte_order_mark_reads_and_maps(capsys, tmp_path):
    """A file saved with a UTF-8 byte-order mark (Windows editors) was 'not valid TOML
    (Invalid statement (at line 1, column 1))'; a map's workers parse the file's text
    again, so they must read it too."""
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + b'name = "bom"\nfields = ["u"]\n[parameters]\nbeta = 1.0\n'
                     b'[energy]\nkinetic = "u_t**2/2"\n'
                     b'bond = "(u_next - u)**2/2 + beta*(u_next - u)**4/4"\n')
    code, out, err = _cli(capsys, "coefficients", "--model", str(path), "--k", "1")
    assert code == 0, err
    code, out, err = _cli(capsys, "map", "--model", str(path), "--param", "beta=1,2", "--k",
                          "1,2", "--theory-only", "--out", str(tmp_path / "m"))
    assert code == 0, err


def test_an_overdamped_carrier_is_said(capsys, tmp_path):
    """Lossy FPUT (R = gamma u_t^2 / 2) at gamma = 5, k = 1: gamma / 2 > omega (0.96), the
    carrier's damped frequency is -0.19i (no oscillation: u'' + gamma u' + omega^2 u = 0),
    yet coefficients printed 'MI (focusing)' with a gain and no word. The note says the
    carrier is overdamped; at gamma = 0.01 nothing is said."""
    import json

    lossy = ('name = "fl"\nfields = ["u"]\n[parameters]\nbeta = 1.0\ngamma = 0.01\n'
             '[energy]\nkinetic = "u_t**2/2"\nbond = "(u_next - u)**2/2 + '
             'beta*(u_next - u)**4/4"\n[dissipation]\nsite = "gamma*u_t**2/2"\n')
    path = tmp_path / "fl.toml"
    path.write_text(lossy)
    notes = {}
    for gamma in (5.0, 0.01):
        code, out, _ = _cli(capsys, "coefficients", "--model", str(path), "--param",
                            f"gamma={gamma}", "--k", "1", "--amplitude", "0.1", "--json")
        assert code == 0
        notes[gamma] = [w for w in json.loads(out)["warnings"] if "damped at" in w]
    # the slow root of s^2 + 5 s + omega^2 = 0, omega^2 = 4 sin^2(1/2): 0.1912
    slow = (5 - math.sqrt(25 - 4 * 4 * math.sin(0.5) ** 2)) / 2
    assert notes[5.0] and "overdamped" in notes[5.0][0] and f"{-slow:.3g}i" in notes[5.0][0]
    assert not notes[0.01]


def test_the_map_api_refuses_wrong_inputs_in_one_line(tmp_path):
    """run_map('x', out) raised an AttributeError from inside, check_rest_stable('fput')
    another; ModelMapParameters took an amplitude of 1e200 and a parameter axis to 1e300
    (each cell's coefficients overflowed later, on a worker)."""
    from energy import ModelError
    from numerics.maps import ModelMapParameters, run_map
    from numerics.models import check_rest_stable

    with pytest.raises(TypeError, match="params must be a MapParameters"):
        run_map("x", tmp_path / "m")
    with pytest.raises(ModelError, match="model must be an energy.Model"):
        check_rest_stable("fput")
    with pytest.raises(ModelError, match="amplitude must be at most 1e"):
        ModelMapParameters.from_model("fput", ("beta", [1, 2]), ("k", [1, 2]), 1e200)
    with pytest.raises(ModelError, match=r"rows \(beta\) must be at most 1e"):
        ModelMapParameters.from_model("fput", ("beta", [1, 1e300]), ("k", [1, 2]), 0.1)
    assert not (tmp_path / "m").exists()


def test_a_spec_with_start_equal_to_stop_says_so():
    """'1:1:3' was 'cannot read SPEC' (it reads; it asks one value three times)."""
    from numerics.maps import parse_spec

    with pytest.raises(ValueError, match=r"start = stop.*single value 1"):
        parse_spec("1:1:3", "--param beta")
    assert list(parse_spec("1:1:1", "--param beta")) == [1.0]


def test_four_wave_takes_no_ring_of_zero_sites():
    """four_wave(..., N=0) answered for the infinite chain while exact_gain(..., N=0)
    refuses it ('N = 0 is a bad ring'): one rule for both."""
    from energy import ModelError, load_model
    from numerics.models import exact_gain, four_wave

    m = load_model("fput")
    for theory in (four_wave, exact_gain):
        with pytest.raises(ModelError, match="N must be an integer"):
            theory(m, 1.0, 0.1, N=0)


def test_another_maps_store_is_refused_before_the_estimate(tmp_path, capsys):
    """Probe 5 leftover: a model map refused another map's store only after its estimate
    (3-5 s of probing cells); numerics.maps.check_store refuses it first, for the model
    map and the paper chain's map alike, and leaves the store as it was."""
    out = str(tmp_path)
    base = ["map", "--model", "fput", "--param", "alpha=1", "--k", "2.6,2.8", "--amplitude",
            "0.1", "--theory-only", "--workers", "1", "--out", out]
    assert _cli(capsys, *base, "--param", "beta=0.8,1.6")[0] == 0
    before = sorted(p.name for p in (tmp_path / "map.zarr").iterdir())
    code, printed, err = _cli(capsys, *base, "--param", "beta=0.8,1.7", "--N", "64",
                              "--exact")
    assert code == 2 and "replace it with --overwrite" in err and err.count("\n") == 1
    assert "estimate" not in printed + err
    assert sorted(p.name for p in (tmp_path / "map.zarr").iterdir()) == before
    paper = ["map", "--alpha", "2.5", "--K-s", "0.01851", "--case", "coupled", "--k",
             "0.8,0.9", "--theory-only", "--workers", "1", "--out", out]
    code, printed, err = _cli(capsys, *paper, "--K-theta", "0.016")
    assert code == 2 and "replace it with --overwrite" in err
    assert "predictions about" not in printed + err  # the paper map's estimate line
