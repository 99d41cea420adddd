"""Render targets into memory. Nothing touches the disk here, so a failing template or
formatter leaves the output directory as it was."""

from __future__ import annotations

import jinja2

from canspec import ir
from canspec.pipeline import paused_gc
from canspec.targets import registry


class GenerationError(Exception):
    pass


def generate(spec: ir.Spec, names: list[str]) -> dict[str, dict[str, bytes]]:
    targets = registry()
    outputs: dict[str, dict[str, bytes]] = {}
    seen: dict[str, str] = {}
    for name in names:
        try:
            with paused_gc():
                produced = targets[name].render(spec)
        except jinja2.TemplateError as exc:
            where = f"{exc.filename}:{exc.lineno}: " if isinstance(exc, jinja2.TemplateSyntaxError) else ""
            raise GenerationError(f"target {name}: template error: {where}{exc}") from None
        except (OSError, ValueError, RuntimeError) as exc:
            raise GenerationError(f"target {name}: {exc}") from None
        for rel in produced:
            if rel in seen:
                raise GenerationError(f"targets {seen[rel]} and {name} both write {rel}")
            seen[rel] = name
        outputs[name] = produced
    return outputs
