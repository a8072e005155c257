import sys
from pathlib import Path

# the tests import helpers that live beside them (_random_systems, check_book_html)
sys.path.insert(0, str(Path(__file__).resolve().parent))
