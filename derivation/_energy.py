"""Any lattice from its energy: equations of motion, Taylor tensors and generated code.

Input: an :class:`energy.Lattice` (fields, parameters, kinetic/bond/site energies). With
W(u_n, u_{n+1}) = bond + site(u_n) per cell and masses m_i from the kinetic energy,

    m_i d^2 u_{i,n}/dt^2 = -d/du_{i,n} [W(u_{n-1}, u_n) + W(u_n, u_{n+1})]      (1)

(Lagrange's equations of the periodic chain; ``equations_of_motion``). Everything else
(dispersion, the multiple-scales NLS with its mean flow, the exact plane wave, the
simulator's force) is computed from the derivatives of W, which are printed here as NumPy
code into one module per model (``model_module_text``): the gradient and Hessian of W for
the force and the Hill operator, and its Taylor tensors at rest (orders 2, 3, 4) for the
NLS. SymPy only differentiates; nothing is solved symbolically, so a model derives in
seconds (the n x n eigenproblems are numerical, in ``numerics.models``).
"""

from __future__ import annotations

import ast
import itertools
from dataclasses import dataclass

import sympy as sp

from energy import Lattice, ModelError, with_body_hash

_FUNCS = {"sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "exp": sp.exp, "log": sp.log,
          "sqrt": sp.sqrt, "sinh": sp.sinh, "cosh": sp.cosh, "tanh": sp.tanh,
          "atan": sp.atan, "Abs": sp.Abs}


def _chain(node, ops):
    """The operands of a left-deep chain of ``ops`` (a + b - c ...), with their signs or
    operators, read without recursion: a 2000-term sum is 2000 levels deep in the tree."""
    items = []
    while isinstance(node, ast.BinOp) and isinstance(node.op, ops):
        items.append((type(node.op), node.right))
        node = node.left
    items.append((None, node))
    return items[::-1]


def to_sympy(tree: ast.Expression, names: dict) -> sp.Expr:
    """SymPy expression of a checked energy tree (``energy._spec``): no ``eval``. Chains of
    + - and of * are read flat (one SymPy Add or Mul), so the recursion goes only as deep
    as the expression's nesting, which ``energy._spec`` bounds."""

    def conv(node):
        if isinstance(node, ast.Expression):
            return conv(node.body)
        if isinstance(node, ast.Constant):
            v = node.value
            return sp.Integer(v) if isinstance(v, int) else sp.Rational(repr(v))
        if isinstance(node, ast.Name):
            return sp.pi if node.id == "pi" else names[node.id]
        if isinstance(node, ast.UnaryOp):
            x = conv(node.operand)
            return -x if isinstance(node.op, ast.USub) else x
        if isinstance(node, ast.BinOp):
            op = type(node.op)
            if op in (ast.Add, ast.Sub):
                terms = [conv(n) if o is not ast.Sub else -conv(n)
                         for o, n in _chain(node, (ast.Add, ast.Sub))]
                return sp.Add(*terms)
            if op is ast.Mult:
                return sp.Mul(*[conv(n) for _, n in _chain(node, (ast.Mult,))])
            a, b = conv(node.left), conv(node.right)
            if op is ast.Div:
                return a / b
            return a**b
        if isinstance(node, ast.Call):
            return _FUNCS[node.func.id](conv(node.args[0]))
        raise ModelError(f"cannot read {ast.dump(node)}")  # the checks make this unreachable

    return conv(tree)


@dataclass(frozen=True)
class Symbols:
    """The symbols of one model: fields at n-1, n, n+1, velocities, parameters."""

    prev: tuple
    here: tuple
    next: tuple
    vel: tuple
    params: tuple

    @classmethod
    def of(cls, lat: Lattice) -> Symbols:
        f = lat.fields
        return cls(prev=tuple(sp.Symbol(f"{x}_prev", real=True) for x in f),
                   here=tuple(sp.Symbol(x, real=True) for x in f),
                   next=tuple(sp.Symbol(f"{x}_next", real=True) for x in f),
                   vel=tuple(sp.Symbol(f"{x}_t", real=True) for x in f),
                   params=tuple(sp.Symbol(p, real=True) for p in lat.parameters))


@dataclass(frozen=True)
class Energies:
    """SymPy forms of one model's energy, with the masses read off the kinetic energy."""

    lattice: Lattice
    symbols: Symbols
    kinetic: sp.Expr
    bond: sp.Expr
    site: sp.Expr
    masses: tuple
    #: Rayleigh functions (None without [dissipation]): site in vel, bond in vel + vel_next
    dissipation: dict | None = None

    @property
    def cell(self) -> sp.Expr:
        """W(u_n, u_{n+1}) = bond + site(u_n)."""
        return self.bond + self.site


def energies(lat: Lattice) -> Energies:
    """Read the energies of ``lat`` into SymPy and check the kinetic energy's form."""
    s = Symbols.of(lat)
    names = {p.name: p for p in s.params}
    names.update({f: x for f, x in zip(lat.fields, s.here)})
    names.update({f + "_next": x for f, x in zip(lat.fields, s.next)})
    names.update({f + "_t": x for f, x in zip(lat.fields, s.vel)})
    kin = to_sympy(lat.tree("kinetic"), names)
    bond = to_sympy(lat.tree("bond"), names)
    site = to_sympy(lat.tree("site"), names)
    for key, ex in (("kinetic", kin), ("bond", bond), ("site", site)):
        if ex.has(sp.zoo, sp.oo, -sp.oo, sp.nan):
            raise ModelError(f"model {lat.name!r}: energy.{key} is infinite or undefined as "
                             "written (a division by zero?)")
    where = f"model {lat.name!r}: energy.kinetic"
    masses = []
    for i, v in enumerate(s.vel):
        m = sp.simplify(sp.diff(kin, v, 2))
        if m.free_symbols & (set(s.vel) | set(s.here)):
            raise ModelError(f"{where}: the mass of {lat.fields[i]} depends on the state "
                             f"({m}); the kinetic energy must be sum_i m_i u_t**2/2, m_i "
                             "constant")
        if m == 0:
            raise ModelError(f"{where}: the mass of {lat.fields[i]} is 0; every field needs a "
                             f"positive mass (a term m*{lat.fields[i]}_t**2/2 with m > 0)")
        masses.append(m)
        for j in range(i + 1, len(s.vel)):
            if sp.simplify(sp.diff(kin, v, s.vel[j])) != 0:
                raise ModelError(f"{where}: couples the velocities of {lat.fields[i]} and "
                                 f"{lat.fields[j]}; it must be diagonal")
    rest = sp.expand(kin - sum(m * v**2 / 2 for m, v in zip(masses, s.vel)))
    if sp.simplify(rest) != 0:
        raise ModelError(f"{where}: is not a quadratic form in the velocities (the rest "
                         f"{sp.simplify(rest)} remains)")
    at_rest = {x: 0 for x in s.here + s.next}
    w0 = sp.simplify((bond + site).subs(at_rest))
    if w0.has(sp.I):  # sqrt(u - 1): complex at rest whatever the parameters (numbers alone)
        raise ModelError(f"model {lat.name!r}: the energy is not real at the rest state "
                         f"(every field 0): bond + site there is {w0} (a square root, log or "
                         "fractional power of a quantity negative at rest?)")
    for i, x in enumerate(s.here):
        # net force on field i of a chain at rest: -(dW/du + dW/du_next) at u = 0
        f0 = sp.simplify((sp.diff(bond + site, x) + sp.diff(bond, s.next[i])).subs(at_rest))
        if f0.has(sp.zoo, sp.oo, -sp.oo, sp.nan):
            raise ModelError(f"model {lat.name!r}: the energy is not differentiable at the "
                             f"rest state (every field 0): the force on {lat.fields[i]} there "
                             "is infinite or undefined (sqrt, log or a negative power of a "
                             "quantity that vanishes at rest?)")
        if f0 != 0:
            raise ModelError(f"model {lat.name!r}: the rest state (every field 0) is not an "
                             f"equilibrium: the force on {lat.fields[i]} there is {-f0}")
    return Energies(lat, s, kin, bond, site, tuple(masses), _dissipation(lat, s, names))


def _dissipation(lat: Lattice, s: Symbols, names: dict) -> dict | None:
    """The Rayleigh functions of [dissipation] in SymPy, checked: homogeneous quadratic
    forms in the velocities (coefficients free of the fields and velocities)."""
    if lat.dissipation is None:
        return None
    vel_next = tuple(sp.Symbol(f"{x}_next_t", real=True) for x in lat.fields)
    names = dict(names) | {f + "_next_t": v for f, v in zip(lat.fields, vel_next)}
    out = {}
    for key in lat.dissipation:
        where = f"model {lat.name!r}: dissipation.{key}"
        R = to_sympy(lat.tree("dissipation." + key), names)
        if R.has(sp.zoo, sp.oo, -sp.oo, sp.nan):
            raise ModelError(f"{where}: is infinite or undefined as written")
        v = s.vel + (vel_next if key == "bond" else ())
        C = sp.hessian(R, v)
        if C.free_symbols & (set(v) | set(s.here) | set(s.next)):
            raise ModelError(f"{where}: is not a quadratic form in the velocities with "
                             "constant coefficients (its second derivatives depend on the "
                             "state)")
        vec = sp.Matrix(v)
        rest = sp.simplify(sp.expand(R - (vec.T * C * vec)[0, 0] / 2))
        if rest != 0:
            raise ModelError(f"{where}: is not a quadratic form in the velocities (the rest "
                             f"{rest} is not quadratic)")
        out[key] = C
    return out


def _regular(expr):
    """``expr`` away from the kinks of Abs: the derivatives of Abs give sign (printed as
    numpy.sign, 0 at the kink) and DiracDelta terms, which vanish everywhere but on the
    kink itself and are dropped (the force of a piecewise-smooth energy, as a simulation
    of it evaluates)."""
    if not expr.has(sp.DiracDelta):
        return expr
    return expr.replace(lambda x: isinstance(x, sp.DiracDelta), lambda x: sp.S.Zero)


def equations_of_motion(e: Energies) -> tuple:
    """Accelerations d^2 u_{i,n}/dt^2 of eq. (1), in u_prev, u, u_next (one per field)."""
    s = e.symbols
    back = dict(zip(s.here, s.prev)) | dict(zip(s.next, s.here))
    w_left = e.bond.subs(back, simultaneous=True)  # the bond (n-1, n)
    return tuple(_regular(-(sp.diff(e.cell, x) + sp.diff(w_left, x)) / m)
                 for x, m in zip(s.here, e.masses))


def taylor_tensors(e: Energies, order: int = 4) -> dict:
    """Nonzero derivatives of W at rest over x = (u_n, u_{n+1}), as {index tuple: expr},
    one sorted index tuple per symmetric class, for orders 2..``order``."""
    s = e.symbols
    x = s.here + s.next
    at_rest = {v: 0 for v in x}
    out = {}
    W = e.cell
    for n in range(2, order + 1):
        for idx in itertools.combinations_with_replacement(range(len(x)), n):
            d = W
            for i in idx:
                d = sp.diff(d, x[i])
            val = sp.simplify(_regular(d).subs(at_rest))
            if val.has(sp.zoo, sp.oo, -sp.oo, sp.nan):
                if n == 2:
                    names = [str(x[i]) for i in idx]
                    raise ModelError(f"model {e.lattice.name!r}: the energy's stiffness at "
                                     f"rest d2W/d{names[0]} d{names[1]} is infinite: linear "
                                     "waves are not defined (a power below 2 of a quantity "
                                     "that vanishes at rest?)")
                val = sp.nan  # printed as numpy.nan: the NLS says it is undefined
            if val != 0:
                out[idx] = val
    return out


def _printer():
    from sympy.printing.numpy import NumPyPrinter

    return NumPyPrinter({"fully_qualified_modules": True, "inline": True,
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
    """The generated NumPy module of one model (deterministic: no time, no path)."""
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
    from pathlib import Path

    from common.files import write_text

    path = Path(path)
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
