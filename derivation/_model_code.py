"""The generated NumPy module of a model (``model_module_text``), printed from its
SymPy energies (``_energy.energies``), split from ``_energy``: the gradient and Hessian of
the cell energy W, the simulator's force as one loop over the bonds, the Taylor tensors
at rest and the damping matrices; ``compile_model`` and ``write_builtin_models`` write
it (``make derive``: generated/models/).
"""

from __future__ import annotations

import sympy as sp

from energy import Lattice, with_body_hash

from ._energy import Energies, _regular, energies, lattice_of, taylor_tensors


def _printer():
    from sympy.printing.numpy import NumPyPrinter

    from ._codegen import _Printer

    class Printer(NumPyPrinter):
        """Max and Heaviside (a positive part's, ``_energy._positive_parts``) printed
        elementwise, as Numba compiles them: numpy.maximum, and Heaviside(y) as
        (1 + sign(y))/2, 1/2 at the kink as SymPy's Heaviside(0) and Abs's derivative."""

        _print_Max = _Printer._print_Max  # the coefficients' printer's, one definition

        def _print_Heaviside(self, expr):
            return f"(0.5 + 0.5*numpy.sign({self._print(expr.args[0])}))"

    return Printer({"fully_qualified_modules": True, "inline": True,
                    "allow_unknown_functions": False})


def _body(e: Energies, exprs: list, targets: list, indent: str = "    ") -> list:
    """Lines that unpack x and p, then assign ``targets[i] = exprs[i]`` after a CSE."""
    s = e.symbols
    pr = _printer()
    lines = []
    for i, v in enumerate(s.here + s.next):
        lines.append(f"{indent}{v.name} = _x[{i}]")
    for i, v in enumerate(s.params):
        lines.append(f"{indent}{v.name} = _p[{i}]")
    subexprs, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("_c"), optimizations=None,
                               order="canonical")
    for sym, val in subexprs:
        lines.append(f"{indent}{sym.name} = {pr.doprint(val)}")
    for t, val in zip(targets, reduced):
        lines.append(f"{indent}{t} = {pr.doprint(val)}")
    return lines


def _site_loop_text(e: Energies) -> list:
    """site_functions_all and accelerations_into: the simulator's force as one loop over
    the bonds (n, n + 1), each bond's pulls -dW_bond/du_n and -dW_bond/du_{n+1} computed
    once and added to its two sites (the pull on n + 1 carried to the next bond in a
    scalar), each site's own term -dsite/du_n in the same pass; the ring's closing bond
    (N - 1, 0) before the loop and the last site after it, so no index wraps inside. The
    elementary functions of single sites are computed once per site first
    (site_functions_all). Scalars in the loop body, so Numba keeps them in registers (the
    fused flexMM kernel's form). A field whose bond pulls are equal and opposite (the bond
    depends on differences) carries its pull on the left site and subtracts it, with no
    second expression (a carried negation, ``_b = -_h``, was measured to keep LLVM from
    vectorising the loop: fput 1.7 against 0.27 ns a site on a ring of 5000)."""
    s = e.symbols
    pr = _printer()
    d = len(s.here)
    gh = [_regular(-sp.diff(e.bond, x)) for x in s.here]
    gn = [_regular(-sp.diff(e.bond, x)) for x in s.next]
    st = [_regular(-sp.diff(e.site, x)) for x in s.here]
    sides = {"n": s.here, "l": s.next}
    found = {}
    for ex in gh + gn + st:
        for f in ex.atoms(sp.Function):
            fs = f.free_symbols - set(s.params)
            for key, syms in sides.items():
                if fs and fs <= set(syms):
                    found[f] = (key, f.xreplace(dict(zip(syms, s.here))))
    templates = sorted({t for _, t in found.values()}, key=sp.srepr)
    index = {t: i for i, t in enumerate(templates)}
    repl = {f: sp.Symbol(f"_f{key}{index[t]}", real=True) for f, (key, t) in found.items()}
    gh, gn, st = ([ex.xreplace(repl) for ex in exs] for exs in (gh, gn, st))
    opposite = [sp.expand(a + b) == 0 for a, b in zip(gh, gn)]
    lines = ["", "", f"SITE_FUNCTIONS_ALL = {len(templates)}", "", "",
             "def site_functions_all(_u, _p, _F):",
             '    """F[i, n] = the i-th elementary function of site n\'s fields, every site."""']
    lines += [f"    {v.name} = _p[{i}]" for i, v in enumerate(s.params)]
    lines += ["    for _n in range(_u.shape[1]):"]
    lines += [f"        {v.name} = _u[{i}, _n]" for i, v in enumerate(s.here)]
    lines += [f"        _F[{i}, _n] = {pr.doprint(t)}" for i, t in enumerate(templates)]
    if not templates:
        lines.append("        pass")

    def block(indent, exprs, where):
        """Assignments of exprs {target: expr} after a CSE, the fields and site functions
        they use loaded from ``where`` first."""
        names = [k for k in exprs if exprs[k] != 0]  # a zero pull is left out of its sum
        subexprs, reduced = sp.cse([exprs[k] for k in names],
                                   symbols=sp.numbered_symbols("_c"), optimizations=None,
                                   order="canonical")
        used = set()
        for ex in [v for _, v in subexprs] + list(reduced):
            used |= {str(v) for v in ex.free_symbols}
        out = []
        for key, idx in where.items():
            out += [f"{indent}{v.name} = _u[{i}, {idx}]" for i, v in enumerate(sides[key])
                    if v.name in used]
            out += [f"{indent}_f{key}{i} = _F[{i}, {idx}]" for i in range(len(templates))
                    if f"_f{key}{i}" in used]
        out += [f"{indent}{sym.name} = {pr.doprint(val)}" for sym, val in subexprs]
        out += [f"{indent}{t} = {pr.doprint(val)}" for t, val in zip(names, reduced)]
        return out

    def total(a, *terms):
        """The acceleration of field a from its pulls (zero pulls left out); an opposite
        field's carried value is the previous bond's pull on its left site: subtracted."""
        plus = [t for t, ex in terms if ex != 0 and not (opposite[a] and t == f"_b{a}")]
        force = " + ".join(plus) if plus else "0.0"
        if opposite[a] and gn[a] != 0:
            force = f"{force} - _b{a}"
        m = e.masses[a]
        return force if m == 1 else f"({force})*_r{a}"

    lines += ["", "", "def accelerations_into(_u, _F, _p, _out):",
              '    """out[i, n] = d^2 u_{i,n}/dt^2 on a ring: the equations of motion, bond by '
              'bond (F from site_functions_all)."""',
              "    _N = _u.shape[1]",
              "    if _N == 0:",
              "        return"]
    lines += [f"    {v.name} = _p[{i}]" for i, v in enumerate(s.params)]
    lines += [f"    _r{a} = {pr.doprint(1 / m)}" for a, m in enumerate(e.masses) if m != 1]
    # the closing bond (N - 1, 0): its pull on N - 1 kept for the end, on 0 carried
    first = {f"_w{a}": gh[a] for a in range(d)}
    first |= {f"_b{a}": gn[a] for a in range(d) if not opposite[a]}
    lines += block("    ", first, {"n": "_N - 1", "l": "0"})
    lines += [f"    _b{a} = _w{a}" for a in range(d) if opposite[a] and gn[a] != 0]
    lines += ["    for _n in range(_N - 1):"]
    body = {f"_h{a}": gh[a] for a in range(d)}
    body |= {f"_g{a}": gn[a] for a in range(d) if not opposite[a]}
    body |= {f"_s{a}": st[a] for a in range(d) if st[a] != 0}
    lines += block("        ", body, {"n": "_n", "l": "_n + 1"})
    for a in range(d):
        lines.append(f"        _out[{a}, _n] = "
                     + total(a, (f"_b{a}", gn[a]), (f"_h{a}", gh[a]), (f"_s{a}", st[a])))
    for a in range(d):
        if gn[a] != 0:
            lines.append(f"        _b{a} = _h{a}" if opposite[a] else f"        _b{a} = _g{a}")
    last = {f"_s{a}": st[a] for a in range(d) if st[a] != 0}
    if last:
        lines += block("    ", last, {"n": "_N - 1"})
    for a in range(d):
        lines.append(f"    _out[{a}, _N - 1] = "
                     + total(a, (f"_b{a}", gn[a]), (f"_w{a}", gh[a]), (f"_s{a}", st[a])))
    return lines


def model_module_text(lat: Lattice, e: Energies | None = None, command: str = "") -> str:
    """The generated NumPy module of one model (deterministic: no time, no path). ``lat``:
    a Lattice, or any model ``lattice_of`` reads (a Model, a built-in name, a path)."""
    lat = lattice_of(lat)
    e = e or energies(lat)
    s = e.symbols
    x = s.here + s.next
    d = len(x)
    pr = _printer()
    grad = [_regular(sp.diff(e.cell, v)) for v in x]
    hess = [[_regular(sp.diff(g, v)) for v in x] for g in grad]
    tens = taylor_tensors(e)
    head = [
        "# " + "-" * 77,
        "# GENERATED FILE - DO NOT EDIT BY HAND.",
        f"# Written by {command or 'derivation.compile_model'} from the energy of model "
        f"{lat.name!r}",
        f"# (SymPy {sp.__version__}). Regenerate, never edit.",
        "# " + "-" * 77,
        "",
        f'"""Derivatives of the cell energy W(u_n, u_{{n+1}}) of model {lat.name!r}.',
        "",
        "x = (u_n fields..., u_{n+1} fields...) (first axis), p = parameters in PARAMETERS",
        "order. Every function works on floats (Numba) and on arrays of shape (2 d, ...)",
        "(NumPy); the ``*_into`` forms write into ``out`` of shape (2 d[, 2 d], ...).",
        '"""',
        "",
        "import numpy",
        "",
        f"NAME = {lat.name!r}",
        f"FIELDS = {tuple(lat.fields)!r}",
        f"PARAMETERS = {tuple(lat.parameters)!r}",
        f"MODEL_HASH = {lat.content_hash!r}",
        "",
        "",
        "def masses(_p):",
        '    """Masses m_i of the fields (kinetic energy sum_i m_i u_t**2/2)."""',
    ]
    for i, v in enumerate(s.params):
        head.append(f"    {v.name} = _p[{i}]")
    head.append("    return numpy.array([" + ", ".join(pr.doprint(m) for m in e.masses)
                + "], dtype=float)")
    head += ["", "", "def cell_energy(_x, _p):",
             '    """W = bond + site of the cell (n, n + 1)."""']
    head += _body(e, [e.cell], ["_w"])
    head += ["    return _w + 0.0 * _x[0]", "", "",
             "def cell_gradient_into(_x, _p, _out):",
             '    """out[a] = dW/dx_a."""']
    head += _body(e, grad, [f"_out[{a}]" for a in range(d)])
    head += _site_loop_text(e)
    head += ["", "", "def cell_hessian_into(_x, _p, _out):",
             '    """out[a, b] = d^2 W/dx_a dx_b."""']
    flat = [hess[a][b] for a in range(d) for b in range(d)]
    head += _body(e, flat, [f"_out[{a}, {b}]" for a in range(d) for b in range(d)])
    head += ["", "", "def taylor(_p):",
             '    """Derivatives of W at rest: H (order 2), T (3), Q (4), symmetric arrays."""']
    for i, v in enumerate(s.params):
        head.append(f"    {v.name} = _p[{i}]")
    head += [f"    _H = numpy.zeros(({d}, {d}))", f"    _T = numpy.zeros(({d}, {d}, {d}))",
             f"    _Q = numpy.zeros(({d}, {d}, {d}, {d}))",
             "    _vals = {"]
    for idx, val in tens.items():
        name = "HTQ"[len(idx) - 2]
        head.append(f"        ({name!r}, {idx!r}): {pr.doprint(val)},")
    head += ["    }", "    _arrays = {'H': _H, 'T': _T, 'Q': _Q}",
             "    for (_name, _idx), _v in _vals.items():",
             "        for _perm in _permutations(_idx):",
             "            _arrays[_name][_perm] = _v",
             "    return _H, _T, _Q",
             "", "",
             "def _permutations(idx):",
             "    import itertools",
             "    return set(itertools.permutations(idx))", ""]
    if e.dissipation is not None:
        head += _damping_text(e)
    return with_body_hash("\n".join(head))


def _damping_text(e: Energies) -> list:
    """damping_matrices(p): the Hessians of the Rayleigh functions in the velocities, the
    site's (d, d) over u_t and the bond's (2 d, 2 d) over (u_t, u_next_t). The damping
    force on u_n is -(C_site v_n + B11 v_n + B12 v_{n+1} + B21 v_{n-1} + B22 v_n)."""
    s = e.symbols
    d = len(s.here)
    pr = _printer()
    lines = ["", "", "def damping_matrices(_p):",
             '    """(C_site (d, d), C_bond (2 d, 2 d)): Hessians of the Rayleigh functions '
             'in the velocities."""']
    lines += [f"    {v.name} = _p[{i}]" for i, v in enumerate(s.params)]
    lines += [f"    _S = numpy.zeros(({d}, {d}))", f"    _B = numpy.zeros(({2 * d}, {2 * d}))"]
    for key, arr in (("site", "_S"), ("bond", "_B")):
        C = e.dissipation.get(key)
        if C is None:
            continue
        for a in range(C.shape[0]):
            for b in range(C.shape[1]):
                val = sp.simplify(C[a, b])
                if val != 0:
                    lines.append(f"    {arr}[{a}, {b}] = {pr.doprint(val)}")
    lines += ["    return _S, _B", ""]
    return lines


def compile_model(lat: Lattice, path, command: str = ""):
    """Derive ``lat`` and write its generated module to ``path`` (atomically)."""
    import os
    from pathlib import Path

    from common.files import write_text

    if not isinstance(path, (str, os.PathLike)):  # None: "expected str, bytes or ..."
        raise TypeError(f"path must be the module file to write (a str or os.PathLike), got "
                        f"{type(path).__name__} {path!r}")
    path = Path(path)
    if path.is_dir():  # was an IsADirectoryError after a temporary file beside the folder
        raise ValueError(f"path {str(path)!r} is a folder: give the module file to write in "
                         f"it, such as {str(path / 'model.py')!r}")
    path.parent.mkdir(parents=True, exist_ok=True)
    return write_text(path, model_module_text(lat, command=command))


def write_builtin_models(out_dir) -> list:
    """generated/models/: one module per built-in model (``make derive``)."""
    from pathlib import Path

    from common.files import write_text
    from energy import BUILTIN, builtin, module_name

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    banner = ("# " + "-" * 77 + "\n# GENERATED FILE - DO NOT EDIT BY HAND.\n"
              "# Written by `make derive` (python -m derivation).\n# " + "-" * 77 + "\n")
    paths = [write_text(out_dir / "__init__.py", banner +
                        '"""Generated code of the built-in lattice models (energy/models/*.toml)."""\n')]
    for name in BUILTIN:
        paths.append(compile_model(builtin(name), out_dir / f"{module_name(name)}.py",
                                   command="`make derive` (python -m derivation)"))
    return paths
