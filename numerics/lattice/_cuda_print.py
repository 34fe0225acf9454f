"""Print a model's generated site force as CUDA device functions (for ``_cuda_models``).

The device source is printed from the model's generated module (``generated/models/NAME.py``
or a user model's cached module), never from the model file: the bodies of
``site_functions_all`` and ``accelerations_into`` are parsed (``ast``), checked against a
whitelist (assignments of arithmetic on names, numbers, the arrays ``_u``, ``_F``, ``_p``
and the elementary functions the energy grammar allows; no import, no attribute but
``numpy.<function>``, no call but those functions) and cut into three per-site device
functions, the same operations in the same order as the CPU's loop:

- ``_site_functions(_u, _F, _p, _n, _N)``: the loop body of ``site_functions_all`` for site
  ``_n`` (sin and cos by the fused kernel's polynomial, as ``numerics.models`` compiles it
  on the CPU when every field is within TRIG_LIMIT);
- ``_site_force_{first,inner,last}(_u, _F, _p, _n, _N, _acc, _r, _m, _l)``: site ``_n``'s
  accelerations into ``_acc[a * PER_THREAD + _r]`` (``_m``, ``_l`` its neighbours): the
  bond (n - 1, n) leaves its pull on n (the loop body at n - 1, as the CPU's previous
  iteration), the bond (n, n + 1) and the site's own term give the accelerations (the
  loop body at n); site 0 (first) starts from the CPU's wrap bond, site N - 1 (last) ends
  with its epilogue.

Arrays on the device are flat: ``_u[a, n]`` is printed ``_u[a * _N + n]``. A field or
parameter name reaches this source only as the generated module spells it, a name the
energy parser checked (``energy._expressions``); numbers only as ``repr`` of the generated literal.
"""

from __future__ import annotations

import ast
import inspect
import textwrap

#: the energy grammar's functions (``energy._expressions.FUNCTIONS``) as the generated module
#: prints them -> their device form (sin/cos of the site functions: the polynomial)
_DEVICE_FUNCTIONS = {"sin": "math.sin", "cos": "math.cos", "tan": "math.tan",
                     "exp": "math.exp", "log": "math.log", "sqrt": "math.sqrt",
                     "sinh": "math.sinh", "cosh": "math.cosh", "tanh": "math.tanh",
                     "arctan": "math.atan", "abs": "abs", "maximum": "max",
                     "sign": "_sign"}
#: Python's own functions the printer may call (abs of an Abs, range of the loops)
_BUILTINS = ("abs", "range")
_ARRAYS = ("_u", "_F", "_p", "_out")
_ALLOWED_NODES = (ast.Module, ast.FunctionDef, ast.arguments, ast.arg, ast.Expr,
                  ast.Assign, ast.Name, ast.Load, ast.Store, ast.Constant, ast.BinOp,
                  ast.UnaryOp, ast.Add, ast.Sub, ast.Mult, ast.Div, ast.Pow, ast.USub,
                  ast.UAdd, ast.Call, ast.Attribute, ast.Subscript, ast.Tuple, ast.For,
                  ast.If, ast.Compare, ast.Eq, ast.Return, ast.Pass)


class DeviceSourceError(ValueError):
    """The generated module holds something the device printer does not take."""


def _check(tree: ast.AST, where: str) -> None:
    """Refuse any construct outside the generated force's grammar (see the module)."""
    for node in ast.walk(tree):
        if not isinstance(node, _ALLOWED_NODES):
            raise DeviceSourceError(f"{where}: {type(node).__name__} is not in the generated "
                                    "force's grammar")
        if isinstance(node, ast.Constant) and not isinstance(node.value, (int, float, str)):
            raise DeviceSourceError(f"{where}: constant {node.value!r}")
        if isinstance(node, ast.Constant) and isinstance(node.value, bool):
            raise DeviceSourceError(f"{where}: constant {node.value!r}")
        if isinstance(node, ast.Attribute):
            ok = (isinstance(node.value, ast.Name)
                  and ((node.value.id == "numpy" and node.attr in _DEVICE_FUNCTIONS)
                       or (node.value.id == "_u" and node.attr == "shape")))
            if not ok:
                raise DeviceSourceError(f"{where}: attribute {ast.unparse(node)}")
        if isinstance(node, ast.Call):
            f = node.func
            ok = (isinstance(f, ast.Attribute) and isinstance(f.value, ast.Name)
                  and f.value.id == "numpy") or (isinstance(f, ast.Name)
                                                 and f.id in _BUILTINS)
            if not ok or node.keywords:
                raise DeviceSourceError(f"{where}: call {ast.unparse(node)}")
        if isinstance(node, ast.Name) and not node.id.isidentifier():
            raise DeviceSourceError(f"{where}: name {node.id!r}")


def _parse(f, where: str) -> ast.FunctionDef:
    tree = ast.parse(textwrap.dedent(inspect.getsource(f)))
    _check(tree, where)
    fn = tree.body[0]
    if not isinstance(fn, ast.FunctionDef):
        raise DeviceSourceError(f"{where}: not a function")
    # the docstring goes
    body = [s for s in fn.body if not (isinstance(s, ast.Expr)
                                       and isinstance(s.value, ast.Constant))]
    fn.body = body
    return fn


def _mentions(node: ast.AST, names) -> bool:
    return any(isinstance(n, ast.Name) and n.id in names for n in ast.walk(node))


class _Device(ast.NodeTransformer):
    """Flat indices, the site's neighbours, the device's functions.

    ``index``: the name that replaces ``_n`` (and ``_n + 1`` -> ``plus``); ``trig``: the
    device spelling of sin and cos; ``out``: what ``_out[a, _n] = x`` becomes (None: the
    statement is dropped; "acc": ``_acc[a * PER_THREAD + _r] = x``; "F": kept for _F)."""

    def __init__(self, index: str, plus: str, trig: dict, out: str | None):
        self.index, self.plus, self.trig, self.out = index, plus, trig, out

    def _site(self, node):
        # _n -> index, _n + 1 -> plus, _N - 1 stays
        if isinstance(node, ast.Name) and node.id == "_n":
            return ast.Name(self.index, ast.Load())
        if (isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add)
                and isinstance(node.left, ast.Name) and node.left.id == "_n"
                and isinstance(node.right, ast.Constant) and node.right.value == 1):
            return ast.Name(self.plus, ast.Load())
        return self.visit(node)

    def visit_Subscript(self, node):
        if isinstance(node.value, ast.Name) and node.value.id in ("_u", "_F", "_out"):
            if not (isinstance(node.slice, ast.Tuple) and len(node.slice.elts) == 2):
                raise DeviceSourceError(f"index {ast.unparse(node)}")
            a, n = node.slice.elts
            a, n = self.visit(a), self._site(n)
            if node.value.id == "_out":
                flat = ast.BinOp(ast.BinOp(a, ast.Mult(), ast.Name("PER_THREAD", ast.Load())),
                                 ast.Add(), ast.Name("_r", ast.Load()))
                return ast.Subscript(ast.Name("_acc", ast.Load()), flat, node.ctx)
            flat = ast.BinOp(ast.BinOp(a, ast.Mult(), ast.Name("_N", ast.Load())), ast.Add(), n)
            return ast.Subscript(ast.Name(node.value.id, ast.Load()), flat, node.ctx)
        return self.generic_visit(node)

    def visit_Call(self, node):
        self.generic_visit(node)
        f = node.func
        if isinstance(f, ast.Attribute) and f.value.id == "numpy":
            name = self.trig.get(f.attr, _DEVICE_FUNCTIONS[f.attr])
            node.func = ast.parse(name, mode="eval").body
        return node


def _stmts(stmts, index, plus, trig, out) -> list:
    """Device copies of ``stmts`` (out None: the _out assignments dropped)."""
    t = _Device(index, plus, trig, out)
    res = []
    for s in stmts:
        if out is None and isinstance(s, ast.Assign) and _mentions(s.targets[0], ("_out",)):
            continue
        res.append(t.visit(ast.parse(ast.unparse(s)).body[0]))
    return res


def _function(name: str, args: list, body: list) -> str:
    """The source of ``def name(args): body`` (name and args: this module's own)."""
    fn = ast.parse(f"def {name}({', '.join(args)}):\n    pass\n").body[0]
    fn.body = body or [ast.Pass()]
    return ast.unparse(ast.fix_missing_locations(ast.Module([fn], type_ignores=[])))


def _split_force(fn: ast.FunctionDef):
    """(constants, wrap, loop body, epilogue) of ``accelerations_into``: the prologue's
    statements before the first that reads ``_u``/``_F`` (the parameters and constants),
    the rest of the prologue (the ring's wrap bond), the bond loop's body, and what
    follows the loop (site N - 1)."""
    loops = [i for i, s in enumerate(fn.body) if isinstance(s, ast.For)]
    if len(loops) != 1:
        raise DeviceSourceError("accelerations_into: one bond loop expected")
    i = loops[0]
    pre = [s for s in fn.body[:i] if not isinstance(s, ast.If)
           and not (isinstance(s, ast.Assign) and isinstance(s.targets[0], ast.Name)
                    and s.targets[0].id == "_N")]
    first = next((j for j, s in enumerate(pre) if _mentions(s, ("_u", "_F"))), len(pre))
    return pre[:first], pre[first:], fn.body[i].body, fn.body[i + 1:]


def device_source(code) -> tuple[str, bool]:
    """(source, trig): the device functions ``_site_functions`` and ``_site_force`` of a
    generated model module ``code`` (see the module), and whether its site functions call
    sin or cos (then a position beyond TRIG_LIMIT stops the chain, as the CPU would leave
    the polynomial)."""
    where = f"model module {getattr(code, '__name__', '?')}"
    sites = _parse(code.site_functions_all, where + ".site_functions_all")
    force = _parse(code.accelerations_into, where + ".accelerations_into")
    params = [s for s in sites.body if not isinstance(s, ast.For)]
    loops = [s for s in sites.body if isinstance(s, ast.For)]
    if len(loops) != 1:
        raise DeviceSourceError(f"{where}.site_functions_all: one site loop expected")
    poly = {"sin": "_psin", "cos": "_pcos"}
    trig = any(isinstance(n, ast.Attribute) and n.attr in ("sin", "cos")
               for n in ast.walk(loops[0]))
    src_sites = _function("_site_functions", ["_u", "_F", "_p", "_n", "_N"],
                          _stmts(params + loops[0].body, "_n", "_n", poly, "F"))
    const, wrap, body, epilogue = _split_force(force)
    args = ["_u", "_F", "_p", "_n", "_N", "_acc", "_r"]
    # site 0: the wrap bond, then the loop body at 0; site N - 1: the wrap bond (its
    # forward pull), the loop body at N - 2 (the pull on N - 1), the epilogue; any other
    # site: the body at n - 1 (its pull on n), the body at n
    lib: dict = {}
    first = _stmts(const + wrap, "_n", "_l", lib, "acc") + _stmts(body, "_n", "_l", lib,
                                                                    "acc")
    last = (_stmts(const + wrap, "_n", "_l", lib, "acc") + _stmts(body, "_m", "_n", lib, None)
            + _stmts(epilogue, "_n", "_l", lib, "acc"))
    inner = (_stmts(const, "_n", "_l", lib, "acc") + _stmts(body, "_m", "_n", lib, None)
             + _stmts(body, "_n", "_l", lib, "acc"))
    parts = [_function(f"_site_force_{name}", args + ["_m", "_l"], stmts)
             for name, stmts in (("first", first), ("last", last), ("inner", inner))]
    return "\n\n\n".join([src_sites, *parts]) + "\n", trig


__all__ = ["device_source", "DeviceSourceError"]
