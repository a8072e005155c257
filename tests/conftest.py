import sys
from pathlib import Path

# the tests import helpers that live beside them (check_book_html, compare_records)
sys.path.insert(0, str(Path(__file__).resolve().parent))
