"""The energy grammar: a model's expressions parsed by Python's own parser (:mod:`ast`)
and checked node by node, never evaluated (``energy._spec`` reads the model file and holds
its :class:`Lattice`; the derivation reads SymPy from the checked trees). Only numbers, the
declared names and the elementary functions below pass, bounded in size, nesting and
magnitude, so a model file cannot run code."""

from __future__ import annotations

import ast
import math
import re

#: Elementary functions an energy may call (SymPy names).
FUNCTIONS = ("sin", "cos", "tan", "exp", "log", "sqrt", "sinh", "cosh", "tanh", "atan",
             "Abs")
#: Constants an energy may use.
CONSTANTS = ("pi",)
MAX_EXPRESSION = 20_000  # characters of one energy
MAX_NODES = 10_000  # syntax-tree nodes of one energy
MAX_DEPTH = 60  # nesting, a chain of + - * counted once
MAX_CALL_DEPTH = 4  # functions nested in functions (each level ~4x the derivation time)
MAX_EXPONENT = 64  # |a constant exponent|
MAX_CONSTANT = 1e15  # |a number in an energy|


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
