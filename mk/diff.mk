# canspec diff / revision history (issue 7). Included by the Makefile.
HISTORY := $(SPEC)/history
REVISIONS := $(sort $(wildcard $(HISTORY)/v*/canspec.yaml))
DIFF_FORMAT ?= text

.PHONY: history-check history-diff changelog

history-check:  ## check every reconstructed revision (schema, rules, changelog vs diff)
	$(CANSPEC) check -q $(SPEC) $(dir $(REVISIONS))

history-diff:  ## diff each revision against the next one (DIFF_FORMAT=text|markdown|json)
	@set -e; prev=; for r in $(patsubst %/canspec.yaml,%,$(REVISIONS)) $(SPEC); do \
	  if [ -n "$$prev" ]; then $(CANSPEC) diff $$prev $$r --format $(DIFF_FORMAT); fi; prev=$$r; done

changelog:  ## print the change record as bilingual Markdown
	$(CANSPEC) changelog $(SPEC)

# The revision report published with a release: this spec against the previous revision, the
# computed changes beside the declared change record (RELEASE_OLD: a spec or DBC of the old version).
RELEASE_OLD ?= $(patsubst %/canspec.yaml,%,$(lastword $(REVISIONS)))
RELEASE_REPORT ?= build/release-report.html
.PHONY: release-report

release-report:  ## the release's revision report (HTML): canspec diff $(RELEASE_OLD) $(SPEC) --format html → $(RELEASE_REPORT)
	@mkdir -p $(dir $(RELEASE_REPORT))
	$(CANSPEC) diff $(RELEASE_OLD) $(SPEC) --format html > $(RELEASE_REPORT)
