"""The bus-log pipeline behind `canspec decode` and `canspec plot`: log readers (`logread`, candump
and BLF in bulk), the bulk decoder (`bulk`, `bulktext`), output sinks (`logsinks`), the health
report (`loghealth`) and whole-file decoding for a fleet (`fleet`). Needs the `logs` extra
(`pip install canspec[logs]`). Its public names are re-exported by `canspec` itself; everything
else here is internal."""
