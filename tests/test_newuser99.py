"""A new user's first two hours (newuser99): what the walk found and fixed.

- ``--param`` and ``--branch`` act only on a lattice model. Given to the paper chain's
  flags (no ``--model``) they were dropped without a word: ``coefficients --alpha 2
  --K-s 0.03 --K-theta 0.02 --k 1 --param K_s=0.5`` answered for K_s = 0.03 with exit 0,
  and the same in point, soliton and map (``--time-unit`` alone was refused already).
"""

import pytest

from bench.probe_newuser99 import LJ  # the probe's copy of the file
from cli.app import main
from energy import ModelError, load_model, parse_model

PAPER = ["--alpha", "2", "--K-s", "0.03", "--K-theta", "0.02", "--k", "1"]


def _one_line_error(capsys, argv):
    code = main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1, err
    return err[0]


@pytest.mark.parametrize("command, extra", [
    ("coefficients", []),
    ("point", ["--case", "coupled"]),
    ("soliton", ["--case", "coupled", "--amplitude", "0.005"]),
    ("map", ["--case", "coupled", "--theory-only", "--out", "unused"]),
])
@pytest.mark.parametrize("option", [["--param", "K_s=0.5"], ["--branch", "1"],
                                    ["--param=K_s=0.5"]])
def test_model_options_given_to_the_paper_flags_are_refused(command, extra, option, capsys,
                                                            tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    err = _one_line_error(capsys, [command, *PAPER, *extra, *option])
    name = option[0].split("=", 1)[0]
    assert f"{name} does nothing without --model" in err, err
    assert not (tmp_path / "unused").exists()  # refused before any work


def test_model_options_still_act_with_a_model(capsys):
    assert main(["coefficients", "--model", "diatomic-fput", "--param", "m=3",
                 "--branch", "v", "--k", "1", "--amplitude", "0.05"]) == 0
    assert "m = 3" in capsys.readouterr().out




def _exact_row_and_misses(capsys, argv):
    assert main(argv) == 0
    lines = capsys.readouterr().out.splitlines()
    exact = next(l for l in lines if l.startswith("exact lattice "))
    return exact, [l for l in lines if "which no offset 2 pi j / N" in l]


def test_the_n_a_missed_band_note_advises_samples_that_band(capsys, tmp_path):
    """The LJ chain at k = 1, a = 0.01 on 128 sites: the exact theory finds narrow
    resonance bands (1e-3 wide near offset 1.14) that no ring offset samples, and the note
    named an N that 'does'. On that ring k snapped elsewhere (N = 132: k 0.9817 ->
    0.9996), where the chain's bands lie elsewhere: the point was stable again, with a
    new N advised (145, 151). A user who follows the note must see the band grow."""
    model = tmp_path / "lj.toml"
    model.write_text(LJ)
    base = ["point", "--model", str(model), "--amplitude", "0.01"]
    exact, notes = _exact_row_and_misses(capsys, [*base, "--k", "1", "--N", "128"])
    assert exact.split()[2] == "stable" and notes, (exact, notes)
    import re

    for note in notes:
        # a band 6e-4 wide printed "1.142 to 1.142": its edges with the digits that differ
        lo, hi = re.search(r"band of offsets (\S+) to (\S+) rad/site", note).groups()
        assert float(lo) < float(hi), note
        m = re.search(r"samples: N = (\d+)(?: with --k (\S+))?", note)
        assert m, note
        k = m.group(2) or "1"  # the old text named no k: the user's own
        exact, _ = _exact_row_and_misses(capsys, [*base, "--k", k, "--N", m.group(1)])
        assert exact.split()[2] == "MI", (note, exact)


@pytest.mark.parametrize("command, extra", [("coefficients", []),
                                            ("point", ["--case", "coupled", "--N", "64"])])
def test_the_paper_chains_nls_band_past_half_the_zone_is_said(command, extra, capsys,
                                                              monkeypatch):
    """alpha 2, K_s 0.03, K_theta 0.02, k 1, a 0.5 (A0 = 25): the semi-discrete NLS's case
    II band |q - k| < a sqrt(g) (g = 169) reaches 6.5 rad/site, past the zone; point's gain
    curve (offsets up to pi) then peaked at its end and printed 'fastest growth: offset
    3.142, sidebands q at 2.136 and 2.136' without a word (a model's coefficients say so
    past pi/2). The exact theory is cut short here: only the header's notes are asked."""
    import cli.point

    class _Stop(Exception):
        pass

    def stop(*a, **k):
        raise _Stop

    monkeypatch.setattr(cli.point, "measure_point", stop)  # the header is what is tested
    argv = [command, *PAPER, "--amplitude", "0.5", *extra]
    try:
        main(argv)
    except _Stop:
        pass
    out = capsys.readouterr().out
    warn = [l for l in out.splitlines() if "MI band reaches offset" in l]
    # 6.5 at k = 1, 6.83 at the 64-site ring's k = 0.98175 (g = 186.5)
    assert len(warn) == 1 and "semi-discrete case II to 6." in warn[0], out
    assert "lower the amplitude" in warn[0]


def test_no_wide_band_note_at_the_readmes_amplitude(capsys):
    # the README's material at a = 0.02: band 0.18 rad/site, far inside pi/2
    assert main(["coefficients", "--alpha", "2.0", "--K-s", "0.03", "--K-theta", "0.02",
                 "--k", "1.2"]) == 0
    assert "MI band reaches" not in capsys.readouterr().out


def test_a_model_maps_shares_print_in_the_figures_order_fresh_or_resumed(capsys, tmp_path):
    """A simulated model map printed its MI shares in the store's variable order: simulated,
    semidiscrete, exact, fourwave when fresh, simulated, fourwave, exact, semidiscrete when
    the same command reopened the finished store. Both now follow the figure's panels:
    semi-discrete NLS, four-wave, exact lattice, simulated."""
    argv = ["map", "--model", "fput", "--param", "beta=1:1.5:2", "--k", "1,2", "--amplitude",
            "0.1", "--N", "16", "--workers", "1", "--out", str(tmp_path / "m")]
    orders = []
    for _ in range(2):  # fresh, then the finished store reopened
        assert main(argv) == 0
        orders.append([l.split(":")[0].removeprefix("MI share, ")
                       for l in capsys.readouterr().out.splitlines()
                       if l.startswith("MI share, ")])
    assert orders[0] == orders[1] == ["semidiscrete", "fourwave", "exact", "simulated"]


INVERTED = """name = "inverted"
fields = ["u"]
[parameters]
beta = 1.0
[energy]
kinetic = "u_t**2/2"
bond = "-(u_next - u)**2/2 + beta*(u_next - u)**4/4"
"""


def test_a_rest_state_that_is_no_minimum_names_the_file_or_values_and_the_fix(capsys,
                                                                              tmp_path):
    """A sign slip, -(u_next - u)**2/2: omega^2 = -4 sin^2(k/2) < 0 at every k. The error
    named neither the file (every other error of a model file does) nor what to change."""
    (tmp_path / "inv.toml").write_text(INVERTED)
    err = _one_line_error(capsys, ["coefficients", "--model", str(tmp_path / "inv.toml"),
                                   "--k", "1"])
    assert err.startswith(f"flexmm: error: {tmp_path / 'inv.toml'}: model 'inverted': the "
                          "rest state is not a minimum"), err
    assert "check the signs of its stiffness terms" in err
    # Klein-Gordon with C = -1, omega0 = 0.5: omega^2 = 0.25 - 4 sin^2(k/2) < 0 past k = 0.505
    err = _one_line_error(capsys, ["point", "--model", "klein-gordon", "--param", "C=-1",
                                   "--param", "omega0=0.5", "--k", "1"])
    assert err.startswith("flexmm: error: --param C=-1, --param omega0=0.5: model "
                          "'klein-gordon': the rest state is not a minimum"), err


CROSS = """name = "cross-chain"
fields = ["u", "v"]
branch = "u"
[parameters]
w0 = 1.5
kappa = 0.3
[energy]
kinetic = "u_t**2/2 + v_t**2/2"
bond = "(u_next - u)**2/2 + (u_next - u)**4/4 + kappa*(u_next - u)**2*v"
site = "w0**2*v**2/2"
"""


@pytest.mark.parametrize("k", ["1", "2"])
def test_a_flat_branch_says_g1_is_zero_at_every_k(k, capsys, tmp_path):
    """v is an on-site oscillator coupled to u only through the cubic kappa r^2 v: its
    branch is omega = w0 at every k (no linear coupling), so v_g = g1 = 0 exactly and the
    NLS is undefined for that reason. At k = 1 (v is branch 1: above u's 2 sin(1/2) =
    0.96) the command said g1 was below float64's resolution and to give k >= 1.7, where
    the branches swap (2 sin(k/2) = 1.5 at k = 1.696); at k = 2 it said g1 = 0."""
    (tmp_path / "cross.toml").write_text(CROSS)
    assert main(["coefficients", "--model", str(tmp_path / "cross.toml"), "--k", k,
                 "--branch", "v", "--amplitude", "0.05"]) == 0
    out = capsys.readouterr().out
    assert "omega (1/time)                                 1.5" in out
    assert f"undefined: g1 = d^2 omega/dk^2 = 0 at k = {k} (no dispersion" in out


def test_the_slow_point_note_names_the_waves_that_take_minutes():
    """The note a slow point prints named only a busy machine or a first compile; a wave
    near a harmonic resonance (the cross chain at k 0.49, 3 omega ~ w0: 65 s against 3.5 s
    at its other k, kernels compiled, same machine) or at a large amplitude (the paper
    chain at A0 = 25: 3.5 min) is slow for its own reason, which the user can change."""
    import cli._slow

    for note in (cli._slow.SLOW_MODEL_POINT, cli._slow.SLOW_PAPER_POINT):
        assert "large amplitude" in note and "resonance" in note


def test_the_paper_points_unsampled_band_note_names_a_ring_of_the_same_k(capsys):
    """The README's material at a = 0.005 on 64 sites (k 1.2 -> 2 pi 12/64): its exact band
    (offsets below 0.047) holds no offset of the ring (2 pi/64 = 0.098). The note named
    N = 134, whose k snaps to 2 pi 26/134 = 1.219, another carrier; a ring that keeps k
    is a multiple of 16 (64/gcd(12, 64)): 144 (2 pi/144 = 0.0436, inside the band)."""
    base = ["point", "--alpha", "2.0", "--K-s", "0.03", "--K-theta", "0.02", "--amplitude",
            "0.005", "--case", "coupled", "--start", "travelling"]
    assert main([*base, "--k", "1.2", "--N", "64"]) == 0
    note = next(l for l in capsys.readouterr().out.splitlines()
                if "holds no offset 2 pi j / N" in l)
    assert "N = 144 with --k 1.17809725 samples it" in note, note
    assert main([*base, "--k", "1.17809725", "--N", "144"]) == 0
    out = capsys.readouterr().out
    assert "2 pi 27/144" in out  # the same k: 27/144 = 12/64
    assert next(l for l in out.splitlines() if l.startswith("exact lattice")).split()[2] == "MI"


def test_the_table_says_which_nls_it_shows(capsys):
    """`flexmm table` is the paper's continuum NLS, and said so nowhere: a user who then ran
    `point` at the blue point, case II, read 'semi-discrete NLS: stable' against the
    table's 'MI (focusing)'. The semi-discrete NLS reverses both case II verdicts: blue
    g2 = -36.25 (stable), green g2 > 0 (MI) (`coefficients` at the paper's materials;
    docs/theory.md: its mean flow, which the paper leaves out)."""
    assert main(["table"]) == 0
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert last.startswith("these are the paper's continuum NLS"), last
    assert "blue coupled: stable" in last and "green coupled: MI" in last
    assert "rotation" not in last  # case I: both NLS agree at both points


def test_the_rest_state_error_names_the_lowest_frequency():
    """A bond with the wrong sign and a site spring c: omega^2(k) = c - 4 sin^2(k/2) by hand,
    lowest at k = pi (0.5 - 4 = -3.5); the error named the first negative k (0.72, -0.0123
    there), not the worst (newuser99's left note)."""
    from numerics.models import check_rest_stable

    m = load_model(parse_model('name = "neg"\nfields = ["u"]\n[parameters]\nc = 0.5\n'
                               '[energy]\nkinetic = "u_t**2/2"\n'
                               'bond = "-(u_next - u)**2/2"\nsite = "c*u**2/2"\n'))
    with pytest.raises(ModelError, match=r"omega\^2 = -3.5 < 0 at k = 3.142 \(its lowest\)"):
        check_rest_stable(m)
