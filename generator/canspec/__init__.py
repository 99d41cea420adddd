"""canspec: one machine-readable CAN/JSON protocol spec, generated into every target."""

__version__ = "0.1.0"
