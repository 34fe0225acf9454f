"""Newuser 101's findings: what a new user's first two hours turned up (docs/models.md's
losses and point sections)."""

from __future__ import annotations

import pytest

# the probe's files: a two-field chain of the user's own (a linear cross term in the bond, a
# quartic bond on u, an on-site v) and its twin with u damped: MI at k 1, a 0.1 (0.0033
# /time), the carrier damped at 2.4e-4
from bench.probe_newuser101 import LOSSY as TWOFIELD_LOSSY
from bench.probe_newuser101 import TWOFIELD
from energy import load_model
from numerics.maps import ModelPointSpec, measure_point


@pytest.fixture(scope="module")
def twofield_lossy(tmp_path_factory):
    path = tmp_path_factory.mktemp("nu101") / "twofield-lossy.toml"
    path.write_text(TWOFIELD_LOSSY)
    return load_model(path)


def test_a_lossy_points_estimate_covers_the_runs_it_makes(twofield_lossy):
    """A lossy point's runs go on past the exact theory's peak time (to 1.5x it, at least
    the lossless run's length) until A(t) has halved; its estimate was of runs of the
    lossless T (2800 here), while they ran to 5565 (at gamma 2e-5: to 9.5e4, 8 s for an
    estimated 1 s). The estimate's T must reach as far as the runs do."""
    seen = []
    point = measure_point(ModelPointSpec(twofield_lossy, 1.0, 0.1, N=64, simulate=True,
                                         seeds=1), on_estimate=seen.append)
    sim = point.as_dict()["simulated"]
    peak = point.as_dict()["exact lattice"]["amplification_time"]
    assert len(seen) == 1
    # the runs reach the exact theory's peak before they may stop (the rule itself)
    assert sim["t_end"] >= peak
    # the estimate is of runs at least as long as those made (its T their cap)
    assert seen[0].t_end >= sim["t_end"]
    assert seen[0].at_most


def test_four_wave_names_why_a_pair_near_another_branch_is_unrated(tmp_path):
    """At eta 0 the two-field chain's u is an FPUT beta chain (alpha 0) and v a linear chain
    of its own; at k 2.8 (a 0.1, 256 sites) the u pair's waves near pi lie 0.06 below the
    v branch, within 4 couplings, and ``_isolated`` leaves them unrated. The four-wave row
    said 'a driven wave too large to be slaved', a process a chain without a cubic term
    has none of; its reason is the crossing, and the rate it would have is FPUT's own."""
    from numerics.models import four_wave

    path = tmp_path / "twofield.toml"
    path.write_text(TWOFIELD)
    model = load_model(path).with_params(eta=0.0)
    fw = four_wave(model, 2.8, 0.1, N=256)
    assert fw.verdict == "undefined"
    assert "driven wave" not in fw.undefined
    assert "crossing" in fw.undefined
    # the u chain alone: FPUT alpha 0, beta 1 at the same ring k (0.0282 /time)
    alone = four_wave(load_model("fput").with_params(alpha=0.0, beta=1.0), 2.8, 0.1, N=256)
    assert alone.verdict == "MI"
    rate = float(fw.undefined.split("about ")[1].split(" ")[0])
    # the reason prints 3 significant digits: within 0.5% of the lone chain's rate
    assert abs(rate / alone.gain - 1) < 5e-3


def test_a_zero_mode_that_is_no_symmetry_is_refused_with_its_field_and_the_remedy(tmp_path):
    """site = "u**3" alone: K(0) = 0 (u is free at k = 0) but the energy is not invariant
    under a uniform shift, so the NLS has no mean flow to solve; the refusal gave only the
    mode vector [1.] and "not supported"."""
    from energy import ModelError
    from numerics.models import nls

    path = tmp_path / "cubic-site.toml"
    path.write_text('name = "cubic-site"\nfields = ["u"]\n[parameters]\nD = 0.5\n[energy]\n'
                    'kinetic = "u_t**2/2"\nbond = "D*(u_next - u)**2"\nsite = "u**3"\n')
    with pytest.raises(ModelError) as err:
        nls(load_model(path), 1.0)
    msg = str(err.value)
    assert "\n" not in msg
    assert "field u" in msg and "on-site stiffness" in msg and "(u_next - u)" in msg


def test_case_with_a_model_says_the_case_is_the_model(capsys):
    """--case coupled beside --model: the refusal told to give --param values, which pick
    no case; the paper chain's cases are the models flexmm and flexmm-rotation."""
    from cli.app import main

    assert main(["point", "--model", "fput", "--k", "1", "--amplitude", "0.1",
                 "--case", "coupled"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "--case" in err
    assert "--model flexmm (coupled)" in err and "flexmm-rotation (rotation)" in err
