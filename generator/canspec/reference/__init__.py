"""The reference implementation in Python, read straight from the IR: the codec every generated
language is tested against, candump log lines, bus load, JSON value checks."""
