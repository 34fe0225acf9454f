"""A finished model map run again (a user re-drawing its figure, or a script that runs
every map of a study): nothing is estimated, since nothing is computed; the store is still
verified and the figure drawn again."""

from __future__ import annotations

from cli.app import main


def test_a_finished_map_run_again_measures_no_cell(tmp_path, capsys):
    argv = ["map", "--model", "fput", "--param", "beta=0.5,1", "--k", "1,2", "--amplitude",
            "0.1", "--theory-only", "--workers", "1", "--out", str(tmp_path / "m")]
    assert main(argv) == 0
    first = capsys.readouterr().out
    assert "estimate: about" in first and "none needed" not in first
    (tmp_path / "m" / "map.png").unlink()
    assert main(argv) == 0
    again = capsys.readouterr().out
    assert "estimate: none needed" in again and "estimate: about" not in again
    assert "4 of 4 cells already done (checksums verified)" in again
    assert (tmp_path / "m" / "map.png").exists()  # the figure made again
