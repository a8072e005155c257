# Two commands from a fresh clone (GNU make and Python 3.11 are all that is needed):
#   make book   builds the book into book/_build/html (executing every chapter)
#   make test   runs the README's test command
# Each creates .venv if it is missing and installs requirements.txt whenever it changed since the
# last install (the stamp .venv/.requirements-installed). Also: make reproduce, make clean.

PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.requirements-installed

.PHONY: book test reproduce clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

$(STAMP): requirements.txt pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -r requirements.txt
	touch $(STAMP)

test: $(STAMP)
	$(BIN)/python -m pytest

book: $(STAMP)
	$(BIN)/jupyter-book build book -W --keep-going
	@echo "The book is in book/_build/html: open book/_build/html/index.html in a browser."

reproduce: $(STAMP)
	$(BIN)/python -m fdsc reproduce --out out
	@echo "The reproduction record is out/reproduction.json."

clean:
	rm -rf book/_build out
