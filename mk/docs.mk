# Protocol handbook: `make docs` builds the static site (site/, gitignored) from generated/docs/
# with MkDocs + Material (mkdocs.yml). Strict: a broken link, anchor or missing page fails it.
MKDOCS ?= $(PYTHON) -m mkdocs
export NO_MKDOCS_2_WARNING := 1

.PHONY: docs docs-gen docs-serve

docs-gen:  ## regenerate only generated/docs/ (the Markdown pages, SVG diagrams and nav)
	$(CANSPEC) gen $(SPEC) -o $(OUT) --target docs

docs: docs-gen  ## build the static HTML handbook into site/ (offline, with search)
	$(MKDOCS) build --strict --clean

docs-serve: docs-gen  ## preview the handbook on http://127.0.0.1:8000
	$(MKDOCS) serve --strict

# The handbook as one PDF (not part of `make gen`: it needs WeasyPrint and fonts-noto-cjk,
# installed by .ci/setup.d/75-pdf.sh). Same spec, same bytes.
DOCS_PDF ?= build/handbook.pdf
.PHONY: docs-pdf

docs-pdf:  ## the bilingual PDF handbook: cover, contents, history, every page of the site (→ $(DOCS_PDF))
	$(CANSPEC) pdf $(SPEC) -o $(DOCS_PDF)
