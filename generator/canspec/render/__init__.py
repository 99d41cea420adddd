"""Stage 3 — text: the Jinja environment of each template folder and static files with their
header (environment), one literal interface per language (literals), the external formatters
(formatters) and the atomic writer (writer)."""
