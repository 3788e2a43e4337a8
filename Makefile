# motion-futures. The README's two commands are `make demo` and `make test`.
SHELL := /bin/bash
.DEFAULT_GOAL := help

VENV := .venv
PY := $(VENV)/bin/python
VITE := ./node_modules/.bin/vite
PORT ?= 4173
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
DATA ?=

.PHONY: help demo test test-python test-web typecheck test-e2e models data vectors bench results strips deps chromium release

help:
	@echo "make demo    build the site and serve it on http://127.0.0.1:$(PORT)/ (needs Node only)"
	@echo "make test    install everything a fresh machine needs, then run every test"
	@echo "make models  retrain and re-export everything in public/ (DATA=PATH for your own data)"
	@echo "make bench   browser and native timings into docs/PERFORMANCE.md"
	@echo "make strips look at the motion: held-out futures of each served model at 0-3 s, docs/strips/"
	@echo "make release build the site into release/motion-futures-VERSION.zip (licences and notices inside)"

# --- installs -----------------------------------------------------------------------------
$(VENV)/.installed: requirements.txt
	python3 -m venv $(VENV)
	$(VENV)/bin/pip install --quiet --disable-pip-version-check --upgrade pip
	$(VENV)/bin/pip install --quiet --disable-pip-version-check -r requirements.txt
	touch $@

node_modules/.installed: package.json package-lock.json
	npm ci --no-audit --no-fund --loglevel=error
	touch $@

chromium:
	@if [ ! -x /usr/bin/chromium ]; then \
	  echo "installing Debian chromium for the browser tests"; \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends chromium >/dev/null; \
	fi

deps: $(VENV)/.installed node_modules/.installed chromium

# --- the two README commands --------------------------------------------------------------
demo: node_modules/.installed
	$(VITE) build --logLevel warn
	@echo ""
	@echo "  motion-futures is at http://127.0.0.1:$(PORT)/   (Ctrl+C stops it)"
	@echo ""
	$(VITE) preview --host 127.0.0.1 --port $(PORT) --strictPort

test: deps
	$(MAKE) --no-print-directory test-python test-web typecheck test-e2e

test-python: $(VENV)/.installed
	$(PY) -m pytest

test-web: node_modules/.installed
	./node_modules/.bin/vitest run --config vitest.config.ts

typecheck: node_modules/.installed
	./node_modules/.bin/tsc --noEmit -p tsconfig.json

test-e2e: node_modules/.installed chromium
	./node_modules/.bin/vitest run --config tests/e2e/vitest.e2e.config.ts

# --- artefacts -----------------------------------------------------------------------------
data: $(VENV)/.installed
	$(PY) -m export data $(if $(DATA),--data $(DATA))

vectors: $(VENV)/.installed
	$(PY) -m export vectors

models: data
	$(PY) -m export models $(if $(DATA),--data $(DATA))
	@# The shared test vectors are cut from the default data; a site built from your data skips them.
	$(if $(DATA),,$(PY) -m export vectors)

results: $(VENV)/.installed
	$(PY) -m export results

# Look at the motion: held-out walk, run, jump and dance futures of each served model at 0-3 s (docs/strips/).
strips: $(VENV)/.installed
	$(PY) -m export strips

bench: deps
	$(PY) -m export bench

# --- release ---------------------------------------------------------------------------------
# A versioned zip of the built site with LICENSE, THIRD_PARTY_NOTICES.md and DATA_NOTICE.md.
release: node_modules/.installed
	node scripts/release.mjs
