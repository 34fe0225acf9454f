"""What a new user found doing the docs' "your own lattice" workflow from a fresh clone (a
chain of pendula with a nonlinear spring: coefficients, a point, a map interrupted and
resumed, its store in xarray), each reproduced small."""

from __future__ import annotations

from cli.app import main as cli

#: a 2 x 2 map of FPUT on a small ring, with the exact and four-wave theories
FPUT_EXACT = ["map", "--model", "fput", "--param", "alpha=1", "--param", "beta=0.8,1.6",
              "--k", "2.6,2.8", "--amplitude", "0.1", "--N", "16", "--theory-only",
              "--workers", "1"]


def test_a_store_of_more_theories_asked_with_fewer_says_which_options_continue_it(
        tmp_path, capsys):
    """The map's own store asked again with --theory-only (a user re-running it cheaper, to
    see its summary) was refused as "of other theories (...; a --theory-only map without
    --exact has no exact columns to continue, a store made before the four-wave columns
    none of those)": neither is what happened. Now it says the store holds more than is
    asked, and which options continue it. Fails on the old tree."""
    out = ["--out", str(tmp_path / "m")]
    assert cli([*FPUT_EXACT, "--exact", *out]) == 0
    capsys.readouterr()
    assert cli([*FPUT_EXACT, *out]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert "of more theories than this one asks (semidiscrete exact fourwave stored, " \
           "semidiscrete asked" in err and "give its --exact" in err
    assert cli([*FPUT_EXACT, "--exact", *out]) == 0  # the remedy said: it continues
    assert "estimate: none needed" in capsys.readouterr().out


def test_the_docs_import_public_names_only():
    """docs/gpu.md told readers `from numerics.maps._gpu import gpu_status` (and
    simulate_cells_gpu), private modules, where numerics.maps exports both: a reader copies
    what the page shows. Every import a page shows is of a public module. Fails on the old
    tree (gpu.md)."""
    import re
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    pages = [root / "README.md", *sorted((root / "docs").glob("*.md"))]
    private = [(p.name, m.group(0)) for p in pages for m in re.finditer(
        r"^\s*(?:>>> |\.\.\. )?(?:from|import) [\w.]*\._\w+", p.read_text(), flags=re.M)]
    assert not private, private


def test_a_map_interrupted_before_its_store_says_no_cell_had_started(tmp_path, capsys,
                                                                    monkeypatch):
    """Ctrl-C during a map's estimate (before its store exists) said "nothing was written
    to OUT/map.zarr; the cells that were running were not kept": none were. Fails on the
    old tree."""
    import numerics.maps as maps

    def interrupted(params):
        raise KeyboardInterrupt

    monkeypatch.setattr(maps, "probe_model_cell", interrupted)
    out = tmp_path / "m"
    assert cli([*FPUT_EXACT, "--out", str(out)]) == 130
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"flexmm: interrupted (SIGINT); nothing was written to {out / 'map.zarr'}"
                   ", no cell had started: run the same command again to start"], err
