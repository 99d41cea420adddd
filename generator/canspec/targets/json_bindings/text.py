"""Documentation text of the JSON bindings: what a field or value is, in one line, and that
line made safe for each language's comments (spec text may hold newlines, quotes, `*/`)."""

from __future__ import annotations

import re
import textwrap

from canspec import ir
from canspec.ir.json_fields import FieldRule, Pair, Plan
from canspec.render.literals import PYTHON

PY_LINE = 100  # generated Python stays within this width


def one_line(text: str) -> str:
    return re.sub(r"\s+", " ", text).strip()


def both(en: str, zh: str) -> str:
    """`English / 中文`, or the English alone when there is no Chinese."""
    return f"{one_line(en)} / {one_line(zh)}" if zh.strip() else one_line(en)


def sentence(*parts: str) -> str:
    """The non-empty parts joined by spaces."""
    return " ".join(one_line(p) for p in parts if p.strip())


def label(v: ir.JsonEnumValue) -> str:
    return both(v.label, v.label_zh)


def paren(v: ir.JsonEnumValue) -> str:
    """`English (中文)`, or the English alone."""
    return f"{one_line(v.label)} ({one_line(v.label_zh)})" if v.label_zh.strip() else one_line(v.label)


def field_doc(r: FieldRule) -> str:
    """One line describing a field: meaning, type, unit, range, precision, sentinels, Chinese name."""
    f = r.field
    parts = [f.type]
    if f.unit:
        parts.append(f.unit)
    if r.has_range:
        parts.append(f"[{r.lo}, {r.hi}]")
    if f.decimals is not None:
        parts.append(f"{f.decimals} decimal{'' if f.decimals == 1 else 's'} (documented)")
    parts += [f"{s.value} = {s.name}" for s in r.sentinels]
    if r.enum is not None:
        parts.append("one of " + ", ".join(f"{e.value} ({e.name})" for e in r.enum.values))
    desc = f.desc.strip().rstrip(".")
    return sentence(desc + "." if desc else "", ", ".join(parts) + ".", f.zh)


def summary(m: ir.JsonMessage) -> str:
    return sentence(m.desc, m.zh) or m.name


def heading(m: ir.JsonMessage) -> str:
    """`name: description 中文`, or the name alone."""
    text = sentence(m.desc, m.zh)
    return f"{m.name}: {text}" if text else m.name


def echo_clause(pair: Pair) -> str:
    """What a reply copies from its request, as its doc says it: ": its `bn` is the request's"."""
    return "".join(f": its `{k}` is the request's" for k in pair.echoed)


def receives(plan: Plan) -> str:
    return f"{plan.receiver} receives {', '.join(plan.messages)}."


def without_receiver(plan: Plan) -> str:
    """How the whole-protocol reader tells the messages apart."""
    return f"Without it: {'; '.join(plan.rules)}." if plan.rules else "Without it: no message is accepted (the protocol has none)."


def party_doc(p: ir.JsonParty) -> str:
    return sentence(p.desc, f"({one_line(p.zh)})" if p.zh.strip() else "") or p.name


def doc_lines(text: str, width: int = 92) -> list[str]:
    """Doc-comment text as lines of at most `width` characters."""
    return textwrap.wrap(one_line(text), width, break_long_words=False, break_on_hyphens=False)


# --- per language ---------------------------------------------------------------------------


def py_wrap(text: str, indent: int, width: int = PY_LINE) -> str:
    """Docstring text wrapped to `width`, continuation lines indented by `indent` spaces."""
    return ("\n" + " " * indent).join(textwrap.wrap(PYTHON.doc(text), width - indent, break_long_words=False, break_on_hyphens=False))


def ts_doc(text: str) -> str:
    """Text inside a JSDoc comment: `*/` would end it."""
    return one_line(text).replace("*/", "*\\/")
