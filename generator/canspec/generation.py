"""Render targets into memory. Nothing touches the disk here, so a failing template or
formatter leaves the output directory as it was."""

from __future__ import annotations

import multiprocessing
import os
from concurrent.futures import ProcessPoolExecutor

import jinja2

from canspec import ir
from canspec.pipeline import paused_gc
from canspec.targets import Target, registry


class GenerationError(Exception):
    pass


def _render_one(target: Target, spec: ir.Spec) -> dict[str, bytes]:
    try:
        return target.render(spec)
    except jinja2.TemplateError as exc:
        where = f"{exc.filename}:{exc.lineno}: " if isinstance(exc, jinja2.TemplateSyntaxError) else ""
        raise GenerationError(f"target {target.name}: template error: {where}{exc}") from None
    except (OSError, ValueError, RuntimeError) as exc:
        raise GenerationError(f"target {target.name}: {exc}") from None
    except Exception as exc:  # a bug in a target: still one clear line, and nothing written
        raise GenerationError(f"target {target.name}: internal error: {type(exc).__name__}: {exc} (please report)") from None


_SPEC: ir.Spec | None = None  # the spec a forked worker renders (inherited, not pickled)


def _render_in_worker(name: str) -> dict[str, bytes]:
    assert _SPEC is not None
    return _render_one(registry()[name], _SPEC)


def generate(spec: ir.Spec, names: list[str]) -> dict[str, dict[str, bytes]]:
    """Render the named targets. With several cores they render in forked processes (rendering
    is CPU-bound Python, and the external formatters then overlap with it); results come back
    in target order, and the first failure in that order is raised."""
    global _SPEC
    targets = registry()
    workers = min(len(names), os.cpu_count() or 1)
    with paused_gc():
        if workers > 1 and "fork" in multiprocessing.get_all_start_methods():
            _SPEC = spec
            try:
                with ProcessPoolExecutor(max_workers=workers, mp_context=multiprocessing.get_context("fork")) as pool:
                    # Slow targets first so that the pool stays busy to the end.
                    order = sorted(names, key=lambda n: -targets[n].cost)
                    futures = {name: pool.submit(_render_in_worker, name) for name in order}
                    results = {name: futures[name].exception() or futures[name].result() for name in names}
            finally:
                _SPEC = None
        else:
            results = {}
            for name in names:
                try:
                    results[name] = _render_one(targets[name], spec)
                except GenerationError as exc:
                    results[name] = exc
    outputs: dict[str, dict[str, bytes]] = {}
    seen: dict[str, str] = {}
    for name in names:
        produced = results[name]
        if isinstance(produced, BaseException):
            raise produced
        for rel in produced:
            if rel in seen:
                raise GenerationError(f"targets {seen[rel]} and {name} both write {rel}")
            seen[rel] = name
        outputs[name] = produced
    return outputs
