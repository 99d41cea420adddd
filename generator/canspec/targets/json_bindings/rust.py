"""The Rust bindings of a JSON protocol: a serde crate (formatted by rustfmt at generation time)
whose checks live in `rt.rs`, a real source file copied with the generated header. Types,
literals, identifiers and signatures are computed here."""

from __future__ import annotations

from canspec import ir
from canspec.ir import json_fields as jsonmodel
from canspec.ir.json_fields import Branch, FieldRule, MessageModel, Pair, Plan, ProtocolModel
from canspec.render.environment import render, static_file
from canspec.render.formatters import rustfmt
from canspec.render.literals import RUST
from canspec.targets.json_bindings import names, text

# Rust integer types, narrowest first: a field holds its declared type's range in the first that fits.
RUST_INTS = (("u8", 0, 2**8 - 1), ("i8", -(2**7), 2**7 - 1), ("u16", 0, 2**16 - 1), ("i16", -(2**15), 2**15 - 1),
             ("u32", 0, 2**32 - 1), ("i32", -(2**31), 2**31 - 1), ("u64", 0, 2**64 - 1), ("i64", -(2**63), 2**63 - 1))
CLIPPY_MAX_ARGS = 7  # clippy::too_many_arguments fires above this many parameters (self included)


def rs_value(r: FieldRule, value: float | str) -> str:
    """A value of the field's Rust type (a number field's as an f64 literal)."""
    return RUST.value(float(value) if r.kind == "number" else value)


def rs_opt_f64(value: float | None) -> str:
    return "None" if value is None else f"Some({RUST.double(value)})"


def rs_type(r: FieldRule) -> str:
    if r.enum is not None:
        return r.enum.name
    if r.kind == "integer":  # bounded within ±(2^53 - 1): canspec check refuses wider integer types
        return next(name for name, lo, hi in RUST_INTS if lo <= (r.type_lo or 0) and (r.type_hi or 0) <= hi)
    return {"number": "f64", "boolean": "bool", "string": "String"}[r.kind]


def src(r: FieldRule) -> str:
    return f"&obj[{RUST.string(r.key)}]"


def range_test(r: FieldRule) -> str:
    """The condition a value within the documented range (or a sentinel) meets."""
    local = names.rust_local(r)
    if r.lo is not None and r.hi is not None:
        test = f"({rs_value(r, r.lo)}..={rs_value(r, r.hi)}).contains(&{local})"
    elif r.lo is not None:
        test = f"{local} >= {rs_value(r, r.lo)}"
    else:
        test = f"{local} <= {rs_value(r, r.hi or 0)}"
    return test + "".join(f" || {local} == {rs_value(r, s.value)}" for s in r.sentinels)


def length_bounds(r: FieldRule) -> tuple[str, str]:
    f = r.field
    return str(f.min_length or 0), "usize::MAX" if f.max_length is None else str(f.max_length)


def reply_params(pm: ProtocolModel, pair: Pair) -> str:
    reply = pm.message(pair.reply)
    keys = ((pair.result,) if pair.result else ()) + pair.extra
    return ", ".join(["&self", *(f"{names.rust_field(reply.rule(k))}: {rs_type(reply.rule(k))}" for k in keys)])


def reply_many_args(pair: Pair) -> bool:
    return 1 + (pair.result is not None) + len(pair.extra) > CLIPPY_MAX_ARGS


def reply_fields(pm: ProtocolModel, pair: Pair) -> list[str]:
    """The reply's struct fields, by shorthand or echoed from the request."""
    request, reply = pm.message(pair.request), pm.message(pair.reply)
    out = []
    for r in reply.data_rules:
        name = names.rust_field(r)
        out.append(f"{name}: self.{names.rust_field(request.rule(r.key))}" if r.key in pair.echoed else name)
    return out


def echo_tests(pm: ProtocolModel, pair: Pair) -> list[str]:
    request, reply = pm.message(pair.request), pm.message(pair.reply)
    return [f"reply.{names.rust_field(reply.rule(k))} == self.{names.rust_field(request.rule(k))}" for k in pair.echoed]


def markers_test(b: Branch) -> str:
    return " || ".join(f"obj.contains_key({RUST.string(k)})" for k in b.markers)


def reads_keys(plan: Plan) -> bool:
    """Whether the plan's reader looks at the object's keys (else it only checks it is an object)."""
    return bool(plan.commands) or any(b.markers for b in plan.plain)


def reader(plan: Plan) -> str:
    return "read_any" if plan.receiver is None else f"read_to_{plan.receiver}"


def unexpected_rule(mm: MessageModel) -> str:
    return f"is not a field of {mm.name}"


def rust_crate_name(protocol: ir.JsonProtocol) -> str:
    return protocol.name.replace("_", "-") + "-json"


def rust_files(spec: ir.Spec, pm: ProtocolModel) -> dict[str, bytes]:
    base = f"json/rust/{pm.protocol.name}"
    receivers = {p.receiver for p in pm.receiver_plans}
    helpers = {
        "rs_str": RUST.string,
        "rust_value": RUST.value,
        "rs_value": rs_value,
        "rs_opt_f64": rs_opt_f64,
        "rs_type": rs_type,
        "src": src,
        "range_test": range_test,
        "length_bounds": length_bounds,
        "reply_params": reply_params,
        "reply_many_args": reply_many_args,
        "reply_fields": reply_fields,
        "echo_tests": echo_tests,
        "markers_test": markers_test,
        "reader": reader,
        "reads_keys": reads_keys,
        "unexpected_rule": unexpected_rule,
        "field": names.rust_field,
        "local": names.rust_local,
        "variant": names.rust_variant,
        "sentinel_const": names.sentinel_const,
        "doc": text.field_doc,
        "label": text.label,
        "heading": text.heading,
        "party_doc": text.party_doc,
        "echo_clause": text.echo_clause,
        "doc_lines": text.doc_lines,
    }
    read_any_doc = "Read any message of the protocol" + (f": {'; '.join(pm.any_plan.rules)}." if pm.messages else " (it has none).")
    lib = render(
        "json_rust/lib.rs.j2",
        spec,
        "json_rust",
        p=pm.protocol,
        pm=pm,
        codes=jsonmodel.ERROR_CODES + jsonmodel.TEXT_ERROR_CODES,
        read_any_doc=read_any_doc,
        silent=[p for p in pm.protocol.parties if p.name not in receivers],
        **helpers,
    )
    cargo = render("json_rust/Cargo.toml.j2", spec, "json_rust", p=pm.protocol, crate=rust_crate_name(pm.protocol))
    return {
        f"{base}/src/lib.rs": rustfmt(lib, f"{base}/src/lib.rs").encode(),
        f"{base}/src/rt.rs": static_file(spec, "json_rust", "json_rust/rt.rs").encode(),
        f"{base}/Cargo.toml": cargo.encode(),
    }
