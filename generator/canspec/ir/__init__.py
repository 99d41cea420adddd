"""Stage 2 — the intermediate representation: frozen dataclasses (model), built in one place
(build) from a validated spec, with the bit layout (bits), J1939 fields (j1939), fingerprints
and the encoding rules every language shares (encoding). Targets read it; they never recompute it.

`from canspec import ir` gives the model's classes (`ir.Spec`, `ir.Message`, ...)."""

from canspec.ir.model import *
