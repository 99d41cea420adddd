"""Runtime tools that run beside a bus: the receive monitor (`monitor`, standard library only; a
generated Python package ships it verbatim as its `monitor.py`), its configuration from the IR
(`supervision`) and the rest-bus simulator (`simulate`, `canspec simulate`). Internal: the
simulator's public names are re-exported by `canspec` itself."""
