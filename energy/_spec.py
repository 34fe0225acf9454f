"""A lattice model as data: fields, parameters and the energy of one unit cell.

The model file (TOML) is the contract; :class:`Lattice` is the same thing in Python. The
energy expressions are checked here with Python's own parser (:mod:`ast`), never evaluated:
only numbers, the declared names and a fixed list of elementary functions are allowed, so a
model file cannot run code. SymPy reads them later (``derivation``), from the checked tree.
"""

from __future__ import annotations

import ast
import builtins
import functools
import hashlib
import json
import keyword
import math
import numbers
import os
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType

#: Elementary functions an energy may call (SymPy names).
FUNCTIONS = ("sin", "cos", "tan", "exp", "log", "sqrt", "sinh", "cosh", "tanh", "atan",
             "Abs")
#: Constants an energy may use.
CONSTANTS = ("pi",)
# Letters and digits, single underscores between them. Unambiguous (each '_' starts a new
# group), so matching is linear in the name's length; the old ``(?:_?[A-Za-z0-9]+)*``
# backtracked exponentially on a long name ending in a character it refuses.
_NAME = re.compile(r"[A-Za-z][A-Za-z0-9]*(?:_[A-Za-z0-9]+)*")
#: The longest field or parameter name.
MAX_NAME = 64
#: Suffixes the generator gives a field (u_prev = u_{n-1}, u_next = u_{n+1}, u_t = du_n/dt):
#: no field or parameter may end in one.
_SUFFIXES = ("_next", "_prev", "_t")
#: Names the generated module uses itself (its imports, module constants and functions):
#: a field or parameter of the same name would shadow them.
GENERATOR_NAMES = frozenset({
    "numpy", "numba", "itertools", "math", "NAME", "FIELDS", "PARAMETERS", "MODEL_HASH",
    "BODY_SHA256", "SITE_FUNCTIONS_ALL", "masses", "cell_energy", "cell_gradient_into",
    "site_functions_all", "accelerations_into", "cell_hessian_into", "taylor",
    "damping_matrices"})
#: Every name a field or parameter may not take: Python's keywords and built-ins (the
#: generated code is Python), the generator's own names, the functions and constants.
RESERVED = frozenset(keyword.kwlist) | frozenset(keyword.softkwlist) | frozenset(
    n for n in dir(builtins) if not n.startswith("_")) | GENERATOR_NAMES
#: Bounds on what a model file may ask of the derivation (checked before SymPy sees it).
MAX_FILE_BYTES = 256 * 1024
MAX_TEXT = 4096  # description, references
MAX_FIELDS = 8
MAX_PARAMETERS = 64
MAX_EXPRESSION = 20_000  # characters of one energy
MAX_NODES = 10_000  # syntax-tree nodes of one energy
MAX_DEPTH = 60  # nesting, a chain of + - * counted once
MAX_CALL_DEPTH = 4  # functions nested in functions (each level ~4x the derivation time)
MAX_EXPONENT = 64  # |a constant exponent|
MAX_CONSTANT = 1e15  # |a number in an energy|
MAX_VALUE = MAX_CONSTANT  # |a parameter's value|, |a carrier's amplitude|
_KEYS = {"name", "description", "fields", "parameters", "energy", "branch", "references",
         "dissipation"}
_ENERGY_KEYS = ("kinetic", "bond", "site")
#: Rayleigh dissipation functions (optional table [dissipation]): quadratic forms in the
#: velocities of cell n (``site``) and of cells n, n + 1 (``bond``), coefficients from the
#: parameters.
_DISSIPATION_KEYS = ("site", "bond")


class ModelError(ValueError):
    """A model that cannot be used, with one line that says why and where."""


def _fail(where: str, message: str):
    raise ModelError(f"{where}: {message}")


def _short(text, limit: int = 60) -> str:
    """``repr`` of a user's text, cut to ``limit`` characters (error lines stay one line)."""
    text = str(text).strip()
    if len(text) > limit:
        text = text[:limit - 15] + " ... " + text[-10:]
    return repr(text)


def check_name(where: str, kind: str, name) -> str:
    """A field or parameter name: letters and digits with single '_' between them, at most
    MAX_NAME characters, not reserved (see :data:`RESERVED`) and not ending in a suffix the
    generator gives a field (_next, _prev, _t)."""
    if not isinstance(name, str):
        _fail(where, f"{kind} name must be a string, got {type(name).__name__} {_short(name)}")
    if len(name) > MAX_NAME:
        _fail(where, f"{kind} name {_short(name)} is longer than {MAX_NAME} characters")
    if not _NAME.fullmatch(name):
        _fail(where, f"{kind} name {_short(name)} is not valid (ASCII letters a-z, A-Z and "
                     "digits, single '_' between them, starting with a letter"
                     + (": spell a Greek letter out, 'theta' for '\u03b8')"
                        if not name.isascii() else ")"))
    if name.endswith(_SUFFIXES):
        _fail(where, f"{kind} name {name!r} ends in {name[name.rindex('_'):]!r}, which the "
                     "generator gives fields (u_prev, u_next, u_t): rename it")
    if name in FUNCTIONS or name in CONSTANTS:
        _fail(where, f"{kind} name {name!r} is a function or constant of the energies: "
                     "rename it")
    if name in RESERVED:
        why = ("a Python keyword" if keyword.iskeyword(name) or keyword.issoftkeyword(name)
               else "a name the generated code uses" if name in GENERATOR_NAMES
               else "a Python built-in")
        _fail(where, f"{kind} name {name!r} is reserved ({why}): rename it")
    return name


@dataclass(frozen=True)
class Lattice:
    """One lattice model: a periodic chain of identical unit cells with nearest-neighbour bonds.

    The energy per cell n is ``kinetic + bond + site`` where, for each field ``u``,
    ``u`` is u_n, ``u_next`` is u_{n+1} and ``u_t`` is du_n/dt. The kinetic energy is a
    diagonal positive quadratic form in the velocities, ``bond`` couples cell n to n + 1
    only, ``site`` depends on cell n only. The rest state (every field 0) must be an
    equilibrium. Equations of motion, dispersion, the NLS and the simulator's force all come
    from these three expressions (``derivation.derive_model``).

    Parameters
    ----------
    name : str
        Identifier (letters, digits, '-' and '_').
    fields : tuple of str
        Degrees of freedom per cell, in order.
    parameters : mapping str -> float
        Parameter names and their default values.
    kinetic, bond, site : str
        The energy expressions (Python/SymPy syntax, ``**`` for powers).
    description : str
        One line.
    branch : str or None
        The field whose branch commands use by default (None: the lowest branch).
    references : str
        Where the model comes from.
    source : str
        Where it was read from (a path, ``builtin:NAME`` or ``python``).
    """

    name: str
    fields: tuple
    parameters: MappingProxyType
    kinetic: str
    bond: str
    site: str = "0"
    description: str = ""
    branch: str | None = None
    references: str = ""
    source: str = "python"
    dissipation: MappingProxyType | None = None
    _trees: dict = field(default_factory=dict, repr=False, compare=False, hash=False)

    def __post_init__(self):
        where = f"model {self.name!r}" if isinstance(self.name, str) else "model"
        if not isinstance(self.name, str) or len(self.name) > MAX_NAME or not re.fullmatch(
                r"[A-Za-z][A-Za-z0-9_-]*", self.name):
            where = "model"
            _fail(where, f"name must be ASCII letters, digits, '-' or '_', starting with a "
                         f"letter (at most {MAX_NAME}), got {_short(self.name)}")
        for key in ("description", "references", "source"):
            text = getattr(self, key)
            if not isinstance(text, str):
                _fail(where, f"{key} must be a string, got {type(text).__name__} "
                             f"{_short(text)}")
            if key != "source" and len(text) > MAX_TEXT:
                _fail(where, f"{key} is {len(text)} characters long (at most {MAX_TEXT})")
        flds = self.fields
        if isinstance(flds, str) or not isinstance(flds, (list, tuple)) or not flds:
            _fail(where, f"fields must be a non-empty list of names, got {_short(flds)}")
        if len(flds) > MAX_FIELDS:
            _fail(where, f"{len(flds)} fields: at most {MAX_FIELDS} (the derivation's fourth-"
                         "order tensors grow as the fourth power of the fields)")
        for f in flds:
            check_name(where, "field", f)
        if len(set(flds)) != len(flds):
            _fail(where, f"fields repeat a name: {list(flds)}")
        object.__setattr__(self, "fields", tuple(flds))
        if not isinstance(self.parameters, (dict, MappingProxyType)):
            _fail(where, "parameters must be a mapping of name to default value, got "
                         f"{type(self.parameters).__name__}")
        params = dict(self.parameters)
        if len(params) > MAX_PARAMETERS:
            _fail(where, f"{len(params)} parameters: at most {MAX_PARAMETERS}")
        for p, v in params.items():
            check_name(where, "parameter", p)
            if p in flds:
                _fail(where, f"parameter {p!r} clashes with the field of the same name")
            params[p] = check_value(f"{where}: parameter {p}", v)
        object.__setattr__(self, "parameters", MappingProxyType(params))
        for key in _ENERGY_KEYS:
            text = getattr(self, key)
            if not isinstance(text, str) or not text.strip():
                _fail(where, f"energy.{key} must be an expression (a string), got {text!r}")
            self._trees[key] = _checked_tree(f"{where}: energy.{key}", text,
                                             self._allowed(key))
        if self.branch is not None and self.branch not in flds:
            _fail(where, f"branch {_short(self.branch, 40)} is not one of the fields "
                         f"{list(flds)}")
        _check_kinetic(where, self._trees["kinetic"], self.fields)
        self._check_dissipation(where)

    def _check_dissipation(self, where: str):
        diss = self.dissipation
        if diss is None:
            return
        if not isinstance(diss, (dict, MappingProxyType)):
            _fail(where, "[dissipation] must be a table with site and/or bond, got "
                         f"{type(diss).__name__}")
        extra = sorted(str(k) for k in set(diss) - set(_DISSIPATION_KEYS))
        if extra:
            _fail(where, f"unknown dissipation key(s) {', '.join(extra)} (known: site, bond)")
        if not diss:
            _fail(where, "[dissipation] is empty: give site and/or bond (or leave it out)")
        out = {}
        for key in _DISSIPATION_KEYS:
            if key not in diss:
                continue
            text = diss[key]
            if not isinstance(text, str) or not text.strip():
                _fail(where, f"dissipation.{key} must be an expression (a string), got "
                             f"{_short(text)}")
            tree = _checked_tree(f"{where}: dissipation.{key}", text,
                                 self._allowed("dissipation." + key))
            _check_rayleigh(f"{where}: dissipation.{key}", tree)
            self._trees["dissipation." + key] = tree
            out[key] = text
        object.__setattr__(self, "dissipation", MappingProxyType(out))

    def _allowed(self, key: str) -> set:
        names = set(self.parameters) | set(FUNCTIONS) | set(CONSTANTS)
        if key.startswith("dissipation."):  # velocities and parameters only
            names |= {f + "_t" for f in self.fields}
            if key == "dissipation.bond":
                names |= {f + "_next_t" for f in self.fields}
            return names
        if key == "kinetic":
            return names | {f + "_t" for f in self.fields}
        names |= set(self.fields)
        if key == "bond":
            names |= {f + "_next" for f in self.fields}
        return names

    @property
    def n_fields(self) -> int:
        return len(self.fields)

    def tree(self, key: str) -> ast.Expression:
        """The checked syntax tree of energy ``key`` (kinetic, bond or site) or of a
        dissipation function (``dissipation.site``, ``dissipation.bond``)."""
        return self._trees[key]

    @property
    def lossy(self) -> bool:
        """Whether the model has a [dissipation] table."""
        return self.dissipation is not None

    def canonical(self) -> dict:
        """What defines the equations (not the defaults, the description or the source).
        A model without [dissipation] has no key for it: its hash is the lossless one."""
        out = {"name": self.name, "fields": list(self.fields),
               "parameters": sorted(self.parameters),
               "energy": {k: ast.dump(self._trees[k]) for k in _ENERGY_KEYS}}
        if self.dissipation is not None:
            out["dissipation"] = {k: ast.dump(self._trees["dissipation." + k])
                                  for k in self.dissipation}
        return out

    @functools.cached_property
    def content_hash(self) -> str:
        """sha256 of :meth:`canonical`: the key of the derived code's cache (computed once
        per object: a frozen Lattice's content does not change; ~0.3 ms a call, asked per
        map cell and per theory)."""
        text = json.dumps(self.canonical(), sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()

    def with_energy(self, **changes) -> Lattice:
        """A copy with some of name, fields, parameters, kinetic, bond, site replaced."""
        kw = {k: getattr(self, k) for k in ("name", "fields", "parameters", "kinetic", "bond",
                                           "site", "description", "branch", "references",
                                           "source", "dissipation")}
        kw.update(changes)
        return Lattice(**kw)

    def values(self, params: dict | None = None) -> dict:
        """Defaults overridden by ``params`` (unknown names refused, values checked)."""
        out = dict(self.parameters)
        for p, v in (params or {}).items():
            if p not in out:
                raise ModelError(f"model {self.name!r} has no parameter {p!r} (it has: "
                                 f"{', '.join(self.parameters) or 'none'})")
            out[p] = check_value(f"parameter {p}", v)
        return out


def check_value(where: str, v) -> float:
    """A parameter value (or a carrier's amplitude): a finite real number (not a bool, a
    string or a complex) of size at most ``MAX_VALUE``, the bound on a number in an energy
    (beyond it a coefficient's powers overflow: g2 of FPUT at alpha = 1e100 is inf)."""
    if isinstance(v, bool) or not isinstance(v, numbers.Real):
        raise ModelError(f"{where} must be a real number, got {type(v).__name__} {v!r}")
    v = float(v)
    if not math.isfinite(v):
        raise ModelError(f"{where} must be finite, got {v!r}")
    if abs(v) > MAX_VALUE:
        raise ModelError(f"{where} must be at most {MAX_VALUE:g} in size (a model's numbers "
                         f"are bounded so that its coefficients stay finite: rescale its "
                         f"units), got {v!r}")
    return v


_NODES = (ast.Expression, ast.BinOp, ast.UnaryOp, ast.Call, ast.Name, ast.Constant, ast.Load,
          ast.Add, ast.Sub, ast.Mult, ast.Div, ast.Pow, ast.USub, ast.UAdd)


def _checked_tree(where: str, text: str, allowed: set) -> ast.Expression:
    """The syntax tree of one energy, checked node by node and bounded (size, nesting,
    constants, exponents) before anything else reads it. Every check is one pass."""
    if len(text) > MAX_EXPRESSION:
        _fail(where, f"the expression is {len(text)} characters long (at most "
                     f"{MAX_EXPRESSION})")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        # Python gives column 0 (or none) where the expression ends too soon ("u +")
        at = (f"at column {exc.offset}" if exc.offset and 0 < exc.offset <= len(text.strip())
              else "at its end (an operator or a bracket left open?)")
        _fail(where, f"syntax error in {_short(text)} {at}: {exc.msg}")
    except (RecursionError, MemoryError):
        _fail(where, f"the expression {_short(text)} has too many terms or is nested too "
                     f"deeply to read (at most {MAX_NODES} terms and symbols, {MAX_DEPTH} "
                     "levels)")
    shown = _short(text)
    nodes = 0
    for node in ast.walk(tree):  # what kinds of node: one pass, before anything reads them
        nodes += isinstance(node, ast.expr)  # numbers, names, operations, calls
        if nodes > MAX_NODES:
            _fail(where, f"the expression {shown} has more than {MAX_NODES} terms and symbols")
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitXor):
            _fail(where, f"'^' is not a power in {shown}: write '**'")
        if not isinstance(node, _NODES):
            _fail(where, f"{type(node).__name__.lower()} is not allowed in {shown} "
                         "(only numbers, names, + - * / ** and function calls)")
    # iterative walk carrying each node's nesting depth and function-call depth; a chain
    # of the same associative operator (a + b + c ...) is one level, as SymPy reads it
    stack = [(tree, 0, 0)]
    while stack:
        node, depth, cdepth = stack.pop()
        if depth > MAX_DEPTH:
            _fail(where, f"the expression {shown} is nested deeper than {MAX_DEPTH} levels")
        if isinstance(node, ast.Constant):
            v = node.value
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                _fail(where, f"constant {_short(v)} is not a real number")
            if not (isinstance(v, int) and v.bit_length() <= 64) and not (
                    isinstance(v, float) and math.isfinite(v)):
                if isinstance(v, int):
                    _fail(where, f"constant {_short(v)} is larger than {MAX_CONSTANT:g}")
                _fail(where, f"constant {v!r} is not finite")
            if abs(v) > MAX_CONSTANT:
                _fail(where, f"constant {_short(v)} is larger than {MAX_CONSTANT:g}")
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
                fn = getattr(node.func, "id", None) or type(node.func).__name__.lower()
                _fail(where, f"unknown function {_short(fn, 30)} (allowed: "
                             f"{', '.join(FUNCTIONS)})")
            if node.keywords or len(node.args) != 1:
                _fail(where, f"{node.func.id}() takes one argument")
            if cdepth + 1 > MAX_CALL_DEPTH:
                _fail(where, f"functions are nested more than {MAX_CALL_DEPTH} deep in {shown}")
            stack.append((node.args[0], depth + 1, cdepth + 1))
            continue
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow):
            _check_exponent(where, node.right, shown)
        if isinstance(node, ast.Name):
            if not isinstance(node.ctx, ast.Load):
                _fail(where, "assignment is not allowed")
            if node.id not in allowed:  # a function's name is not visited: see ast.Call
                _fail(where, _unknown(node.id, allowed))
            continue
        op = type(node.op) if isinstance(node, ast.BinOp) else None
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.operator, ast.unaryop, ast.expr_context)):
                continue
            same = op in (ast.Add, ast.Sub, ast.Mult) and isinstance(child, ast.BinOp) and (
                type(child.op) in ((ast.Add, ast.Sub) if op is not ast.Mult else (ast.Mult,)))
            stack.append((child, depth if same else depth + 1, cdepth))
    return tree


def _constant_value(node):
    """The value of a subtree of numbers, + - * / ** and pi (None if it holds a symbol or
    a function); float arithmetic, bounded: an overflow is infinite."""
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not (
            isinstance(node.value, bool)):
        return float(node.value) if abs(node.value) <= 1e308 else math.inf
    if isinstance(node, ast.Name) and node.id == "pi":
        return math.pi
    if isinstance(node, ast.UnaryOp):
        v = _constant_value(node.operand)
        return None if v is None else (-v if isinstance(node.op, ast.USub) else v)
    if isinstance(node, ast.BinOp):
        a, b = _constant_value(node.left), _constant_value(node.right)
        if a is None or b is None:
            return None
        try:
            op = type(node.op)
            if op is ast.Add:
                return a + b
            if op is ast.Sub:
                return a - b
            if op is ast.Mult:
                return a * b
            if op is ast.Div:
                return a / b if b != 0 else math.inf
            if op is ast.Pow:
                if abs(b) > MAX_EXPONENT:
                    return math.inf
                r = abs(a) ** b
                return r if isinstance(r, float) else math.inf
        except (OverflowError, ZeroDivisionError):
            return math.inf
    return None


def _check_exponent(where: str, node, shown: str):
    v = _constant_value(node)
    if v is not None and not (math.isfinite(v) and abs(v) <= MAX_EXPONENT):
        _fail(where, f"the exponent {_short(ast.unparse(node), 30)} in {shown} is beyond "
                     f"|exponent| <= {MAX_EXPONENT}")


def _unknown(name: str, allowed: set) -> str:
    hint = ""
    if re.search(r"_(next|prev)\d|_prev$|_next_next", name):
        hint = " (couplings beyond the nearest neighbour are not supported: bond couples " \
               "cell n to n + 1 only)"
    elif name.endswith("_next"):
        hint = " (u_next is allowed in energy.bond only)"
    elif name.endswith("_t"):
        hint = (" (velocities are allowed in energy.kinetic and [dissipation] only; "
                "u_next_t in dissipation.bond only)")
    else:  # a typo of a declared name or a function ('betta', 'Sin'): the likely one
        import difflib

        lower = {n.lower(): n for n in allowed}
        close = difflib.get_close_matches(name.lower(), list(lower), n=1, cutoff=0.75)
        hint = f" (did you mean {lower[close[0]]!r}?)" if close else ""
    names = ", ".join(sorted(n for n in allowed if n not in FUNCTIONS and n not in CONSTANTS))
    return f"unknown symbol {_short(name, 40)}{hint}; allowed here: {names}"


def _check_kinetic(where: str, tree: ast.Expression, fields: tuple):
    # A sum of terms c * u_t**2 (c free of velocities), read off the tree without SymPy;
    # derivation re-checks it symbolically (a form that only expands to one is accepted
    # there too).
    terms = []

    def walk(node, sign=1):
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub)):
            walk(node.left, sign)
            walk(node.right, sign if isinstance(node.op, ast.Add) else -sign)
        else:
            terms.append(node)

    walk(tree.body)
    seen = set()
    for t in terms:
        vel = {n.id for n in ast.walk(t) if isinstance(n, ast.Name) and n.id.endswith("_t")}
        text = ast.unparse(t)
        if len(vel) != 1:
            _fail(where, f"energy.kinetic must be a diagonal quadratic form sum_i m_i u_t**2/2"
                         f"; the term {text!r} " + ("has no velocity" if not vel else
                                                   "couples velocities " + ", ".join(
                                                       sorted(vel))))
        seen |= vel
    missing = [f for f in fields if f + "_t" not in seen]
    if missing:
        _fail(where, f"energy.kinetic has no term for field(s) {', '.join(missing)} "
                     f"(every field needs a mass: e.g. '{missing[0]}_t**2/2')")


def _check_rayleigh(where: str, tree: ast.Expression):
    """A Rayleigh function's light check without SymPy: every term of its top-level sum
    holds a velocity (a term without one is not a quadratic form in the velocities);
    ``derivation`` checks the form (homogeneous of degree 2) symbolically and the model
    checks it is positive semi-definite at its parameter values."""
    terms = []

    def walk(node):
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub)):
            walk(node.left)
            walk(node.right)
        else:
            terms.append(node)

    walk(tree.body)
    for t in terms:
        if not any(isinstance(n, ast.Name) and n.id.endswith("_t") for n in ast.walk(t)):
            if _constant_value(t) == 0:
                continue
            _fail(where, f"must be a quadratic form in the velocities; the term "
                         f"{_short(ast.unparse(t))} has no velocity")


def read_model(path: str | Path) -> Lattice:
    """Read a model file (TOML): the format of ``docs/models.md``."""
    if not isinstance(path, (str, os.PathLike)):
        raise ModelError(f"read_model: the path of a model file (.toml) must be a str or "
                         f"os.PathLike, got {type(path).__name__} {path!r}")
    path = Path(path)
    where = str(path)
    try:
        if not path.is_file():
            raise ModelError(f"{where}: no such model file" if not path.exists() else
                             f"{where}: not a regular file (a model file is a .toml file)")
        with path.open("rb") as fh:
            raw = fh.read(MAX_FILE_BYTES + 1)
    except OSError as exc:
        raise ModelError(f"{where}: cannot read the model file ({exc.strerror or exc})") \
            from None
    if len(raw) > MAX_FILE_BYTES:
        raise ModelError(f"{where}: the model file is larger than {MAX_FILE_BYTES // 1024} KiB")
    try:
        text = raw.decode("utf-8-sig")  # a byte-order mark (Windows editors) is no TOML
    except UnicodeDecodeError as exc:
        raise ModelError(f"{where}: the model file is not UTF-8 text (byte {exc.start})") \
            from None
    return parse_model(text, where)


def parse_model(text: str, where: str = "model") -> Lattice:
    """A :class:`Lattice` from the text of a model file."""
    if not isinstance(text, str):
        raise ModelError(f"{where}: the model's text must be a string, got "
                         f"{type(text).__name__}")
    if len(text.encode("utf-8", "surrogatepass")) > MAX_FILE_BYTES:
        raise ModelError(f"{where}: the model file is larger than {MAX_FILE_BYTES // 1024} KiB")
    try:
        data = tomllib.loads(text.removeprefix("\ufeff"))  # a byte-order mark: no TOML
    except tomllib.TOMLDecodeError as exc:
        raise ModelError(f"{where}: not valid TOML ({_short(exc, 200)[1:-1]})") from None
    except (RecursionError, MemoryError):
        raise ModelError(f"{where}: not valid TOML (nested too deeply)") from None
    unknown = sorted(set(data) - _KEYS)
    if unknown:
        _fail(where, f"unknown key(s) {', '.join(unknown)} (known: {', '.join(sorted(_KEYS))})")
    for key in ("name", "fields", "energy"):
        if key not in data:
            _fail(where, f"missing key {key!r}")
    energy = data["energy"]
    if not isinstance(energy, dict):
        _fail(where, "[energy] must be a table with kinetic, bond and site")
    extra = sorted(set(energy) - set(_ENERGY_KEYS))
    if extra:
        _fail(where, f"unknown energy key(s) {', '.join(extra)} (known: kinetic, bond, site)")
    for key in ("kinetic", "bond"):
        if key not in energy:
            _fail(where, f"missing energy.{key}")
    params = data.get("parameters", {})
    if not isinstance(params, dict):
        _fail(where, "[parameters] must be a table of name = default value")
    try:
        return Lattice(name=data["name"], fields=data["fields"], parameters=params,
                       kinetic=energy["kinetic"], bond=energy["bond"],
                       site=energy.get("site", "0"),
                       description=data.get("description", ""),
                       branch=data.get("branch"), references=data.get("references", ""),
                       source=where, dissipation=data.get("dissipation"))
    except ModelError as exc:
        msg = str(exc)
        raise ModelError(msg if msg.startswith(where) else f"{where}: {msg}") from None
