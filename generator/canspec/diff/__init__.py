"""Semantic diff of two protocol revisions (spec, or DBC/ARXML/KCD/SYM) with a breaking-change ladder.

inputs.py  — an argument as a model: a spec compiled, a database through `canspec import` (fromdb.py)
model.py   — the comparison model, built from the IR (`from_spec`)
compare.py — matching (frame ID, name, bit position) and one `Change` per difference
classes.py — the ladder wire > source > compatible > docs and the version-bump suggestion
report.py  — text / markdown / json rendering
history.py — the changelog-vs-diff check behind `canspec check`
"""
