"""Stage 1 — the spec as written: YAML with line numbers (yamlsource), schema-checked documents
(loader), shared layouts expanded (resolve), semantic rules (validate), and the problems they
report (problems). Internal: use `canspec.compile_spec` (the public API is canspec/__init__.py)."""
