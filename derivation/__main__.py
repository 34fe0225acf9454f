"""`python -m derivation --out DIR`: derive and write every file of generated/."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

MODULE_DOC = """NLS coefficients and MI band of rotational waves in a flexible mechanical metamaterial.

Continuum-limit multiple-scales results of Demiquel, Achilleos, Theocharis & Tournat,
"Modulation instability in nonlinear flexible mechanical metamaterials". Equation labels
are the paper's. Case (I): rotation only; case (II): rotation coupled to displacement.
Arguments: carrier wavenumber k (rad per site), inertia alpha, stiffnesses K_s, K_theta;
the MI functions take the NLS nonlinearity g = g2/g1 and the envelope amplitude A0.
"""

LATTICE_DOC = """Semi-discrete NLS coefficients: the multiple-scales derivation repeated on the lattice.

Same functions and arguments as `generated.coefficients`, derived from the discrete
eq. `norm` of Demiquel, Achilleos, Theocharis & Tournat instead of its continuum limit:
the carrier is exact on the lattice (eq. `discrete2`), the cubic terms are the lattice's,
the second harmonic of U has the lattice dispersion (eq. `discrete1` at 2k), and case (II)
includes the induced mean flow (`mean_flow_coefficient`), which the paper sets to zero.
Each tends to the paper's form as k -> 0 (the mean-flow part of g2_coupled excepted).
"""


def write_outputs(out_dir: Path) -> list[Path]:
    """Derive and write every generated file atomically into ``out_dir``; returns paths."""
    from common.files import write_text

    from . import _codegen, _lattice_model, _report, _soliton
    from ._pipeline import ClosedForm, derive

    d = derive()
    files = {
        "coefficients.py": _codegen.module_source(d, MODULE_DOC),
        "lattice_coefficients.py": _codegen.module_source(d, LATTICE_DOC, d.lattice_forms),
        "lattice_model.py": _codegen.module_source(d, _lattice_model.MODULE_DOC,
                                                   _lattice_model.forms(ClosedForm)),
        "soliton.py": _codegen.module_source(d, _soliton.MODULE_DOC,
                                             _soliton.forms(ClosedForm, d)),
        "derivation.md": _report.render(d),
    }
    out_dir.mkdir(parents=True, exist_ok=True)
    # write-then-rename: an interrupted derive never leaves a half-written file
    paths = [write_text(out_dir / name, text) for name, text in files.items()]
    from ._model_code import write_builtin_models

    return paths + write_builtin_models(out_dir / "models")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python -m derivation", description=__doc__)
    parser.add_argument("--out", default="generated", help="output folder (default: generated)")
    args = parser.parse_args(argv)
    t0 = time.perf_counter()
    paths = write_outputs(Path(args.out))
    dt = time.perf_counter() - t0
    for p in paths:
        print(f"wrote {p}")
    print(f"derivation took {dt:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
