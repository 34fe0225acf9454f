"""Print the derived closed forms as a NumPy-only Python module.

Deterministic by construction: fixed SymPy version, canonical CSE ordering, numbered
subexpression names, no timestamps or paths in the output.
"""

from __future__ import annotations

import sympy as sp
from sympy.printing.numpy import NumPyPrinter

BANNER = """\
# -----------------------------------------------------------------------------
# GENERATED FILE - DO NOT EDIT BY HAND.
# Written by `make derive` (python -m derivation --out generated) from the
# SymPy derivation in derivation/ (SymPy {sympy}). Regenerate, never edit.
# -----------------------------------------------------------------------------
"""


class _Printer(NumPyPrinter):
    """NumPy printer whose output broadcasts like the rest of NumPy."""

    def __init__(self):
        super().__init__({"fully_qualified_modules": True, "inline": True,
                          "allow_unknown_functions": False})

    def _print_Max(self, expr):
        args = [self._print(a) for a in sorted(expr.args, key=sp.default_sort_key)]
        out = args[0]
        for a in args[1:]:
            out = f"numpy.maximum({out}, {a})"
        return out

    def _print_Abs(self, expr):
        return f"numpy.abs({self._print(expr.args[0])})"


# Every argument passes this check (the rule of numerics.lattice.checks.real_array, printed
# here because generated code imports numpy only): a bool, a string or a complex number is
# refused, not cast (numpy.asarray(x, dtype=float) reads True as 1.0 and "1.0" as 1.0).
_REAL = '''def _real(name, value):
    """``value`` as a float array; TypeError naming ``name`` unless it holds real numbers
    (a bool, a string or a complex number is refused, not cast)."""
    a = numpy.asarray(value)
    if a.dtype.kind not in "fiu":
        raise TypeError(f"{name} must hold real numbers, got {type(value).__name__} "
                        f"{value!r}"[:200])
    return a.astype(float, copy=False)
'''


def _printed_expr(form):
    """``form.expr`` with each argument named in ``even_in`` replaced by its absolute value
    (a real symbol of the same name: the derivation's is positive, where |x| = x)."""
    even = getattr(form, "even_in", ())
    if not even:
        return form.expr
    return form.expr.xreplace({a: sp.Abs(sp.Symbol(a.name, real=True))
                               for a in form.args if a.name in even})


def _function_source(form, printer):
    args = [str(a) for a in form.args]
    expr = _printed_expr(form)
    matrix = isinstance(expr, sp.MatrixBase)
    exprs = list(expr) if matrix else [expr]
    subs, body = sp.cse(exprs, symbols=sp.numbered_symbols("x"), optimizations=None,
                        order="canonical")
    lines = [f"def {form.name}({', '.join(args)}):"]
    latex = sp.latex(expr)
    lines.append(f'    r"""{form.doc}')
    lines.append("")
    lines.append(f"    Paper: eq. `{form.label}`. Derived closed form:")
    lines.append("")
    lines.append(f"    .. math:: {latex}")
    lines.append("")
    lines.append("    Parameters are floats or arrays (NumPy broadcasting); singular points")
    lines.append("    give inf/nan with NumPy's RuntimeWarning, never an exception.")
    lines.append('    """')
    for a in args:
        lines.append(f"    {a} = _real({a!r}, {a})")
    for sym, val in subs:
        lines.append(f"    {sym} = {printer.doprint(val)}")
    if not matrix:
        lines.append(f"    return {printer.doprint(body[0])}")
        return "\n".join(lines)
    # constant entries (0, 1, ...) broadcast against the arguments to one common shape
    entries = ", ".join(printer.doprint(e) for e in body)
    lines.append(f"    entries = numpy.broadcast_arrays({', '.join(args)}, {entries})"
                 f"[{len(args)}:]")
    lines.append(f"    return numpy.stack(entries).reshape({expr.shape!r} + "
                 "entries[0].shape)")
    return "\n".join(lines)


def module_source(derivation, module_doc, forms=None):
    """Source text of the generated module for ``forms`` (default ``derivation.forms``)."""
    printer = _Printer()
    forms = derivation.forms if forms is None else forms
    names = [f.name for f in forms]
    parts = [
        BANNER.format(sympy=sp.__version__),
        f'"""{module_doc}"""',
        "",
        "import numpy",
        "",
        f"__all__ = {names!r}",
        "",
        "",
        _REAL.rstrip("\n"),
        "",
    ]
    for form in forms:
        parts.append("")
        parts.append(_function_source(form, printer))
        parts.append("")
    return "\n".join(parts).rstrip() + "\n"
