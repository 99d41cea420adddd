"""Stage 3 — text: the one Jinja environment (environment), literal syntax per language
(literals), identifier shapes (names), the external formatters (formatters) and the atomic
writer (writer)."""
