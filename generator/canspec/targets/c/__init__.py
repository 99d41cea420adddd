"""Header-only C99 for ECUs (`c/<protocol>*.h`): model.py and the modules it uses hold the
meaning, templates/c/ the text, check.py what the target refuses. Output is formatted by
clang-format with the committed templates/c/.clang-format, run on private copies of the text
so that generation stays deterministic and atomic."""

from __future__ import annotations

from canspec import ir, resources
from canspec.render.environment import render
from canspec.render.formatters import clang_format_files
from canspec.targets import Target
from canspec.targets.c.check import c_problems
from canspec.targets.c.model import build_model
from canspec.targets.c.names import HEADERS

STYLE_FILE = ".clang-format"
MISRA_RECORD = "MISRA.md"  # the deviation record firmware teams file with the headers


def render_c(spec: ir.Spec) -> dict[str, bytes]:
    if spec.can is None:
        return {}
    model = build_model(spec)
    rendered = {f"{model.prefix}{suffix}": render(template, spec, "c", c=model) for template, suffix in HEADERS}
    style = resources.templates_dir() / "c" / STYLE_FILE
    out = {f"c/{name}": text.encode("utf-8") for name, text in clang_format_files(rendered, style).items()}
    out[f"c/{STYLE_FILE}"] = (resources.templates_dir() / "c" / STYLE_FILE).read_bytes()
    out[f"c/{MISRA_RECORD}"] = render("c/MISRA.md.j2", spec, "c", c=model).encode("utf-8")
    return out


TARGET = Target("c", "header-only C99 (pack/unpack, physical, J1939, VIN, receive monitor)", "c/", render_c, order=30, cost=10, check=c_problems,
                formatters=("clang-format",))
