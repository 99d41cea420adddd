"""The reference models, read straight from the IR: what the tests (and the shared vectors) hold
the generated code against — the codec (`codec`), the JSON value checks (`jsonvalue`) and the
multi-frame text reassembly (`textframes`). Internal: not part of canspec's public API."""
