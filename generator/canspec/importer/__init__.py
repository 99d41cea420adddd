"""Stage 0 — `canspec import`: a DBC (or ARXML, KCD, SYM) the team already has, as a canspec spec.

load.py reads each source through cantools (dbctext.py repairs the dirty DBC lines one sensible
reading exists for), tospec.py turns it into the spec's syntax, merge.py joins several sources,
yamlout.py writes the bundle. Every decision a source did not make is a warning with its
`file:line`; `--strict` makes them errors."""
