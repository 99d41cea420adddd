"""The PDF handbook (`canspec pdf`, `make docs-pdf`): the site's pages as one bilingual,
printable document — cover (protocol, version, spec hash), contents, the change record, then
every page of the site (overview with bus, nodes and J1939 addressing; per message its table,
bit diagram and values; value tables; bus load; JSON protocol; errata).

assemble.py turns the docs target's pages into chapters; document.py adds the cover and the
contents (templates/pdf/); render.py prints the HTML to PDF. Internal: `canspec pdf` is its interface.
"""
