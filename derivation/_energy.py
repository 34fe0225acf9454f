"""Any lattice from its energy: equations of motion, Taylor tensors (the generated code
printed from them: ``_model_code``).

Input: an :class:`energy.Lattice` (fields, parameters, kinetic/bond/site energies). With
W(u_n, u_{n+1}) = bond + site(u_n) per cell and masses m_i from the kinetic energy,

    m_i d^2 u_{i,n}/dt^2 = -d/du_{i,n} [W(u_{n-1}, u_n) + W(u_n, u_{n+1})]      (1)

(Lagrange's equations of the periodic chain; ``equations_of_motion``). Everything else
(dispersion, the multiple-scales NLS with its mean flow, the exact plane wave, the
simulator's force) is computed from the derivatives of W, which are printed as NumPy
code into one module per model (``_model_code.model_module_text``): the gradient and
Hessian of W for the force and the Hill operator, and its Taylor tensors at rest (orders
2, 3, 4) for the NLS. SymPy only differentiates; nothing is solved symbolically, so a
model derives in seconds (the n x n eigenproblems are numerical, in ``numerics.models``).
"""

from __future__ import annotations

import ast
import itertools
from dataclasses import dataclass

import sympy as sp

from energy import Lattice, ModelError

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
    """SymPy expression of a checked energy tree (``energy._expressions``): no ``eval``. Chains of
    + - and of * are read flat (one SymPy Add or Mul), so the recursion goes only as deep
    as the expression's nesting, which ``energy._expressions`` bounds."""

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


def lattice_of(model) -> Lattice:
    """The :class:`Lattice` of ``model``: a Lattice, an ``energy.Model`` (its lattice), or
    what ``energy.resolve_model`` reads (a built-in name, a path, a model file's text)."""
    import os

    from energy import Model, resolve_model

    if isinstance(model, Lattice):
        return model
    if isinstance(model, Model):
        return model.lattice
    if isinstance(model, (str, os.PathLike)):
        return resolve_model(model)
    raise ModelError(f"model must be an energy.Lattice, an energy.Model, a built-in name, a "
                     f"model file's path or its text, got {type(model).__name__}")


def _positive_parts(expr):
    """``expr`` with each positive or negative part written with Abs, c (y + Abs(y)) or
    c (Abs(y) - y) (a contact that opens: ((d0 - r + Abs(d0 - r))/2)**(5/2)), as
    2 c Max(y, 0) (or 2 c Max(-y, 0)): the same function, whose value is an exact 0 past
    the kink, and its derivatives Heaviside(y) Max(y, 0)**(3/2) (printed with sign, as
    Abs's). SymPy distributes the 1/2 over the sum, and the printed
    d0/2 + u/2 - u_next/2 + Abs(d0 + u - u_next)/2 rounds to -1.4e-17 there, whose power
    5/2 is nan (probe 97: the energy along an opened contact read "not real")."""
    if not expr.args:
        return expr
    expr = expr.func(*[_positive_parts(a) for a in expr.args])
    if not expr.is_Add:
        return expr
    for term in expr.args:
        c, rest = term.as_coeff_Mul()
        if not isinstance(rest, sp.Abs) or c == 0:
            continue
        y = rest.args[0]
        for sign in (1, -1):
            left = sp.expand(expr - term - sign * c * y)
            count = 0 if left == 0 else len(sp.Add.make_args(left))
            if count < len(expr.args) - 1:  # y's terms were there
                return _positive_parts(left) + 2 * c * sp.Max(sign * y, 0)
    return expr


def energies(lat: Lattice) -> Energies:
    """Read the energies of ``lat`` into SymPy and check the kinetic energy's form (``lat``:
    a Lattice, or any model ``lattice_of`` reads)."""
    lat = lattice_of(lat)
    s = Symbols.of(lat)
    names = {p.name: p for p in s.params}
    names.update({f: x for f, x in zip(lat.fields, s.here)})
    names.update({f + "_next": x for f, x in zip(lat.fields, s.next)})
    names.update({f + "_t": x for f, x in zip(lat.fields, s.vel)})
    kin = to_sympy(lat.tree("kinetic"), names)
    bond = _positive_parts(to_sympy(lat.tree("bond"), names))
    site = _positive_parts(to_sympy(lat.tree("site"), names))
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
                             f"equilibrium: the force on {lat.fields[i]} there is {-f0}; "
                             "remove the energy's terms linear in the fields (a constant "
                             "force), or write the energy about the equilibrium")
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
    """Accelerations d^2 u_{i,n}/dt^2 of eq. (1), in u_prev, u, u_next (one per field).
    ``e``: the model's ``Energies``, or any model ``energies`` reads."""
    if not isinstance(e, Energies):
        e = energies(e)
    s = e.symbols
    back = dict(zip(s.here, s.prev)) | dict(zip(s.next, s.here))
    w_left = e.bond.subs(back, simultaneous=True)  # the bond (n-1, n)
    return tuple(_regular(-(sp.diff(e.cell, x) + sp.diff(w_left, x)) / m)
                 for x, m in zip(s.here, e.masses))


def _infinite(expr) -> bool:
    return expr.has(sp.zoo, sp.oo, -sp.oo, sp.nan)


def _value_at_rest(raw):
    """A derivative at rest, simplified, unless simplifying makes it infinite where it is
    not: SymPy splits off the parameters' special values as a Piecewise (a Hertz contact
    with precompression d0 written with Abs read ``Piecewise((zoo, Eq(d0, 0)), ...)``,
    and every third and fourth derivative was printed as nan, the NLS undefined at every
    d0, probe 97). Those values are the printed expression's own: it is evaluated at the
    parameters' values, where a non-finite number is said by the NLS."""
    val = sp.simplify(raw)
    return raw if _infinite(val) and not _infinite(raw) else val


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
            val = _value_at_rest(_regular(d).subs(at_rest))
            if _infinite(val):
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
