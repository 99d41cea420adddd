"""Identifier shapes per target language: a name is computed in Python, never built by
concatenation in a template."""

from __future__ import annotations

import re
from functools import lru_cache

C_KEYWORDS = frozenset(
    [
        "auto", "break", "case", "char", "const", "continue", "default", "do", "double", "else", "enum", "extern", "float", "for", "goto", "if", "inline",
        "int", "long", "register", "restrict", "return", "short", "signed", "sizeof", "static", "struct", "switch", "typedef", "union", "unsigned", "void",
        "volatile", "while", "_Bool", "_Complex", "_Imaginary", "bool", "true", "false", "class", "delete", "new", "this", "template", "typename", "namespace"
    ]
    # C++ (the headers compile as C++ too), its alternative operator tokens, and the type names a
    # generated struct uses (a C++ member of that name would change their meaning)
    + [
        "alignas", "alignof", "and", "and_eq", "asm", "bitand", "bitor", "catch", "char8_t", "char16_t", "char32_t", "compl", "concept", "consteval",
        "constexpr", "constinit", "const_cast", "co_await", "co_return", "co_yield", "decltype", "dynamic_cast", "explicit", "export", "friend", "mutable",
        "noexcept", "not", "not_eq", "nullptr", "operator", "or", "or_eq", "private", "protected", "public", "reinterpret_cast", "requires", "static_assert",
        "static_cast", "thread_local", "throw", "try", "typeid", "using", "virtual", "wchar_t", "xor", "xor_eq"
    ]
    + ["int8_t", "int16_t", "int32_t", "int64_t", "uint8_t", "uint16_t", "uint32_t", "uint64_t", "size_t"]
)
RUST_KEYWORDS = frozenset(
    [
        "as", "break", "const", "continue", "crate", "else", "enum", "extern", "false", "fn", "for", "if", "impl", "in", "let", "loop", "match", "mod",
        "move", "mut", "pub", "ref", "return", "self", "Self", "static", "struct", "super", "trait", "true", "type", "unsafe", "use", "where", "while",
        "async", "await", "dyn", "abstract", "become", "box", "do", "final", "macro", "override", "priv", "typeof", "unsized", "virtual", "yield", "try"
    ]
)


_CAMEL = re.compile(r"([a-z0-9])([A-Z])")
_SEPARATORS = re.compile(r"[^A-Za-z0-9]+")


@lru_cache(maxsize=1 << 16)
def _words(name: str) -> tuple[str, ...]:
    """words(), kept: a compile derives the names of each message and signal several times (38,000
    splits of 5,000 names for the Ford DBC's spec)."""
    return tuple(w.lower() for w in _SEPARATORS.split(_CAMEL.sub(r"\1 \2", name)) if w)


def words(name: str) -> list[str]:
    """Split snake_case, camelCase or Title Case text into lower-case words."""
    return list(_words(name))


def snake(name: str) -> str:
    return "_".join(_words(name))


def upper_snake(name: str) -> str:
    return snake(name).upper()


def pascal(name: str) -> str:
    out = "".join(w[:1].upper() + w[1:] for w in _words(name))
    return f"_{out}" if out[:1].isdigit() else out


def humanize(name: str) -> str:
    """English label from an identifier: `manual_assist` → `Manual assist`."""
    text = " ".join(_words(name))
    return text[:1].upper() + text[1:]


def c_ident(name: str) -> str:
    return f"{name}_" if name in C_KEYWORDS else name


def rust_ident(name: str) -> str:
    return f"r#{name}" if name in RUST_KEYWORDS and name not in ("self", "Self", "crate", "super") else (f"{name}_" if name in RUST_KEYWORDS else name)
