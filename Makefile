# Two commands from a fresh clone (GNU make and Python 3.11 are all that is needed):
#   make book   builds the book into book/_build/html (executing every chapter not yet executed
#               for the same sources)
#   make test   runs the README's test command (taking the chapters the build executed from its
#               notebook cache; the results of both in one folder)
# Each creates .venv if it is missing and installs requirements.txt, every package at the version
# of the lock constraints.txt, whenever either changed since the last install (the stamp
# .venv/.requirements-installed). Also: make reproduce, make clean, and
#   make lock   regenerates constraints.txt (needs the package registry; see its header)

PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.requirements-installed
# One folder of chapter results for the book build, the tests and the record (keyed by a hash
# of the sources: results of other code are never read), so that `make book` then `make test`, or
# the reverse, computes each result once; the tests also take each chapter's execution from the
# notebook cache the build filled, and the build the tests'. `make clean` removes it.
RESULTS := $(CURDIR)/book/_build/.fdsc-results

.PHONY: book test reproduce clean lock

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

# pip itself at the locked version first, then everything at the locked versions
$(STAMP): requirements.txt constraints.txt pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet --upgrade pip -c constraints.txt
	$(BIN)/python -m pip install --quiet -r requirements.txt -c constraints.txt
	touch $(STAMP)

test: $(STAMP)
	FDSC_CACHE_DIR=$(RESULTS) $(BIN)/python -m pytest

book: $(STAMP)
	FDSC_CACHE_DIR=$(RESULTS) $(BIN)/jupyter-book build book -W --keep-going
	@echo "The book is in book/_build/html: open book/_build/html/index.html in a browser."

reproduce: $(STAMP)
	FDSC_CACHE_DIR=$(RESULTS) $(BIN)/python -m fdsc reproduce --out out
	@echo "The reproduction record is out/reproduction.json."

clean:
	rm -rf book/_build out

# The lock: a fresh temporary venv, the newest pip, requirements.txt alone (no lock), then every
# installed package with its exact version (`pip freeze --all`: pip, setuptools and wheel too,
# fdsc itself left out). Written to a temporary file first: a failed run leaves the lock as it was.
LOCK_VENV := /tmp/fdsc-lock-venv
lock:
	rm -rf $(LOCK_VENV)
	$(PYTHON) -m venv $(LOCK_VENV)
	$(LOCK_VENV)/bin/python -m pip install --quiet --upgrade pip
	$(LOCK_VENV)/bin/python -m pip install --quiet -r requirements.txt
	{ echo "# The lock: every package that requirements.txt installs (tests and book), at one exact"; \
	  echo "# version each, for CPython 3.11 on Linux x86_64. Used as a constraints file by make, .ci/run"; \
	  echo "# and the README: pip install -r requirements.txt -c constraints.txt"; \
	  echo "# Regenerate it with one command: make lock"; \
	  echo "# (a fresh venv, pip install -r requirements.txt, pip freeze --all --exclude-editable)."; \
	  echo "# Do not edit by hand; change requirements.txt and run make lock."; \
	  $(LOCK_VENV)/bin/python -c 'import platform; print("# generated with CPython", platform.python_version(), "on", platform.system(), platform.machine())'; \
	  $(LOCK_VENV)/bin/python -m pip freeze --all --exclude-editable; } > constraints.txt.tmp
	mv constraints.txt.tmp constraints.txt
	rm -rf $(LOCK_VENV)
