"""The IR owns every fact more than one consumer needs (issue 23): no module outside `ir/` (and
`reference/`, the tests' independent models) computes with a signal's factor or offset, restates
the 11/29-bit identifier limits, or writes the J1939 constants; templates only shape text.

The scan reads the source as Python and Jinja syntax trees, so it sees the arithmetic however it is
spelled: directly on `.factor` / `.offset`, or on a local bound from them (`f = float(sig.factor)`
... `(x - o) / f`). Comparisons stay allowed: a target may branch on a scaling (`factor == 1`),
it may not compute with it. Each rule is shown to catch the code it was written against."""

from __future__ import annotations

import ast
import re
from pathlib import Path

import jinja2
from jinja2 import nodes
from repo_paths import ROOT

PACKAGE = ROOT / "generator" / "canspec"
TEMPLATES = ROOT / "templates"
OWNERS = ("ir", "reference")  # where the facts are computed: the IR, and the oracles that check it independently
SCALE = frozenset({"factor", "offset"})
CONVERSIONS = frozenset({"float", "int", "Fraction", "abs"})  # a scale value converted is still one
# The identifier limits as literals (ir/ids.py holds them) and as the shifts that make them.
# (0x20000000 is left to the log readers: there it is Linux's CAN_ERR_FLAG, not a limit.)
ID_LIMITS = frozenset({0x7FF, 0x1FFFFFFF})
ID_BITS = frozenset({11, 29})
# Static runtime sources under templates/ are shipped verbatim (a copied file carries its constants
# as its own code); the generator's own code and the templates are what this checks.
STATIC = "static"


def _is_scale(node: ast.AST, tainted: set[str]) -> bool:
    """The expression is a factor or offset: the attribute, a local bound from one, a conversion
    of one, or arithmetic on one."""
    if isinstance(node, ast.Attribute):
        return node.attr in SCALE
    if isinstance(node, ast.Name):
        return node.id in tainted
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in CONVERSIONS:
        return any(_is_scale(a, tainted) for a in node.args)
    if isinstance(node, ast.BinOp):
        return _is_scale(node.left, tainted) or _is_scale(node.right, tainted)
    if isinstance(node, ast.UnaryOp):
        return _is_scale(node.operand, tainted)
    return False


def _bound(target: ast.AST, value: ast.AST, tainted: set[str]) -> set[str]:
    """The names an assignment binds to a scale value (`f, o = float(s.factor), float(s.offset)`)."""
    if isinstance(target, (ast.Tuple, ast.List)) and isinstance(value, (ast.Tuple, ast.List)) and len(target.elts) == len(value.elts):
        return set().union(*(_bound(t, v, tainted) for t, v in zip(target.elts, value.elts, strict=True)))
    if isinstance(target, ast.Name) and _is_scale(value, tainted):
        return {target.id}
    return set()


SCOPES = (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef)


def _own(scope: ast.AST) -> list[ast.AST]:
    """The nodes of a scope, not those of the functions and classes inside it."""
    out, todo = [], list(ast.iter_child_nodes(scope))
    while todo:
        node = todo.pop()
        out.append(node)
        if not isinstance(node, SCOPES):
            todo.extend(ast.iter_child_nodes(node))
    return out


def _tainted(own: list[ast.AST], outer: set[str]) -> set[str]:
    """The names of a scope bound to a scale value (and those of the scopes around it)."""
    names = set(outer)
    while True:
        found = set(names)
        for node in own:
            if isinstance(node, ast.Assign):
                for target in node.targets:
                    found |= _bound(target, node.value, found)
        if found == names:
            return names
        names = found


def _computes(node: ast.AST, tainted: set[str]) -> bool:
    if isinstance(node, ast.BinOp):
        return _is_scale(node.left, tainted) or _is_scale(node.right, tainted)
    if isinstance(node, ast.UnaryOp):
        return isinstance(node.op, ast.USub) and _is_scale(node.operand, tainted)
    if isinstance(node, ast.AugAssign):
        return _is_scale(node.value, tainted) or _is_scale(node.target, tainted)
    return False


def scale_arithmetic(source: str) -> list[str]:
    """`line: expression` of every computation with a factor or offset in a Python module."""
    out = []
    todo: list[tuple[ast.AST, set[str]]] = [(ast.parse(source), set())]
    while todo:
        scope, outer = todo.pop()
        own = _own(scope)
        tainted = _tainted(own, outer)
        out += [f"{n.lineno}: {ast.unparse(n)}" for n in own if _computes(n, tainted)]
        todo += [(n, tainted) for n in own if isinstance(n, SCOPES)]
    return sorted(set(out))


def id_limits(source: str) -> list[str]:
    """`line: expression` of every 11/29-bit identifier limit written as a literal or a shift."""
    out = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Constant) and type(node.value) is int and node.value in ID_LIMITS:
            out.append(f"{node.lineno}: 0x{node.value:X}")
        elif (
            isinstance(node, ast.BinOp) and isinstance(node.op, (ast.LShift, ast.Pow)) and isinstance(node.right, ast.Constant) and node.right.value in ID_BITS
        ):
            out.append(f"{node.lineno}: {ast.unparse(node)}")
    return sorted(set(out))


def _modules(owners: tuple[str, ...] = OWNERS) -> list[Path]:
    return sorted(p for p in PACKAGE.rglob("*.py") if p.relative_to(PACKAGE).parts[0] not in owners)


def _templates() -> list[Path]:
    return sorted(p for p in TEMPLATES.rglob("*.j2") if STATIC not in p.relative_to(TEMPLATES).parts)


def test_the_scan_sees_what_it_reads():
    assert len(_modules()) > 100 and len(_templates()) > 40, "the package or the templates moved: point the scan at them"


def test_no_module_outside_the_ir_computes_with_factor_or_offset():
    found = {str(p.relative_to(PACKAGE)): hits for p in _modules() if (hits := scale_arithmetic(p.read_text(encoding="utf-8")))}
    assert not found, f"compute these in ir/ (ir.to_physical, Signal.physical / quotient / runtime_quotient, ...) and read them: {found}"


def test_no_module_outside_the_ir_restates_the_id_limits():
    # the log readers too: an identifier limit is no oracle's own rule
    found = {str(p.relative_to(PACKAGE)): hits for p in _modules(("ir",)) if (hits := id_limits(p.read_text(encoding="utf-8")))}
    assert not found, f"import canspec.ir.ids (MAX_STANDARD_ID, MAX_EXTENDED_ID, max_id, id_text): {found}"


def _template_arithmetic(path: Path) -> list[str]:
    """Jinja expressions that compute with a factor or offset."""
    tree = jinja2.Environment().parse(path.read_text(encoding="utf-8"))

    def scaled(node: nodes.Node) -> bool:
        return any(isinstance(n, nodes.Getattr) and n.attr in SCALE for n in [node, *node.find_all(nodes.Getattr)])

    return [f"{n.lineno}: {type(n).__name__}" for n in tree.find_all((nodes.BinExpr, nodes.Neg)) if any(scaled(c) for c in n.iter_child_nodes())]


# An identifier limit or a J1939 constant written into a template's code (not its comments).
_TEMPLATE_CONSTANT = re.compile(r"\b(0x7FF|0x1FFFFFFF|0x1C000000)(?![0-9A-F])|\b240u\b", re.IGNORECASE)
_COMMENT = re.compile(r"^\s*(//|/\*|\*|#(?!define)|\{#)")


def _template_constants(path: Path) -> list[str]:
    lines = path.read_text(encoding="utf-8").splitlines()
    return [f"{i}: {line.strip()}" for i, line in enumerate(lines, 1) if _TEMPLATE_CONSTANT.search(line) and not _COMMENT.match(line)]


def test_templates_compute_nothing_the_ir_holds():
    found = {str(p.relative_to(TEMPLATES)): hits for p in _templates() if (hits := _template_arithmetic(p) + _template_constants(p))}
    assert not found, f"pass the value from the IR through the target's view: {found}"


# --- each rule catches the code it was written against (as it stood before issue 23) -------------


def test_the_rules_catch_what_they_were_written_against():
    # targets/rust/bits.py rebuilt raw_min / raw_max
    assert scale_arithmetic("def refused(sig):\n    lo = max(sig.raw_min, math.ceil((sig.check_min - sig.offset) / sig.factor))\n")
    # targets/rust/encode.py divided by locals bound from the scaling, in a nested function too
    assert scale_arithmetic("def q(sig, x):\n    f, o = float(sig.factor), float(sig.offset)\n    return (x - o) / f\n")
    assert scale_arithmetic("def q(sig):\n    f = float(sig.factor)\n    def inner(x):\n        return x / f\n    return inner\n") == ["4: x / f"]
    # a name bound from the scaling in one function is not the same name in another
    assert not scale_arithmetic("def a(sig):\n    f = sig.factor\n    return f\ndef b(f, x):\n    return x * f\n")
    # targets/python/fields.py: the raw of physical 0
    assert scale_arithmetic("def zero(sig):\n    return int(-sig.offset / sig.factor)\n")
    assert scale_arithmetic("def shift(sig, x):\n    x += sig.offset\n")
    # a decision on the scaling is not a computation
    assert not scale_arithmetic("def direct(sig):\n    return sig.factor == 1 and sig.offset.denominator == 1\n")
    # spec/validate.py, targets/rust/model.py, targets/vectors/sequences.py, reference/candump*.py
    assert id_limits("limit = 0x1FFFFFFF if extended else 0x7FF\n") == ["1: 0x1FFFFFFF", "1: 0x7FF"]
    assert id_limits("top = (1 << 29) - 1\n") == ["1: 1 << 29"]
    assert id_limits("ok = frame_id <= np.where(extended, 0x1FFFFFFF, 0x7FF)\n") == ["1: 0x1FFFFFFF", "1: 0x7FF"]
    assert not id_limits("mask = 0xFF\n")


def test_the_template_rules_catch_what_they_were_written_against(tmp_path):
    old = tmp_path / "common.h.j2"
    old.write_text("/* J1939 limit 0x1FFFFFFF */\n#define {{ c.macro }}_J1939_ID_MASK 0x1FFFFFFFu\n{{ s.factor * 2 }} {{ -s.offset }}\n", encoding="utf-8")
    assert _template_constants(old) == ["2: #define {{ c.macro }}_J1939_ID_MASK 0x1FFFFFFFu"]
    assert _template_arithmetic(old) == ["3: Mul", "3: Neg"]
