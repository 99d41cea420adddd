"""Which optional extra of canspec (pyproject's `[project.optional-dependencies]`) provides a
module: a command that needs one says what to install instead of failing with a traceback.
`canspec gen`/`check`/`diff` need none of them."""

from __future__ import annotations

# Import name → (distribution, extra). tests/packaging/test_extras.py holds it against pyproject.
MODULE_EXTRA = {
    "numpy": ("numpy", "logs"),
    "pyarrow": ("pyarrow", "logs"),
    "can": ("python-can", "logs"),  # log readers, `canspec simulate`
    "asammdf": ("asammdf", "logs"),
    "matplotlib": ("matplotlib", "logs"),
    "tqdm": ("tqdm", "logs"),
    "weasyprint": ("weasyprint", "pdf"),
    "markdown": ("markdown", "pdf"),
    "cantools": ("cantools", "import"),  # `canspec import`, `canspec diff` of a DBC
}


def install_hint(extra: str) -> str:
    return f"install the {extra} extra: pip install 'canspec[{extra}]'"


def missing_module_hint(exc: BaseException) -> str | None:
    """'<distribution> is missing; install ...' when `exc` is the import error of an extra's module."""
    name = getattr(exc, "name", None) if isinstance(exc, ImportError) else None
    found = MODULE_EXTRA.get((name or "").partition(".")[0])
    return None if found is None else f"{found[0]} is missing; {install_hint(found[1])}"
