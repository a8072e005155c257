from check_book_html import check


def write(tmp_path, name, body):
    (tmp_path / name).write_text(f"<html><body>{body}</body></html>", encoding="utf-8")


def test_clean_page_passes(tmp_path):
    (tmp_path / "_static" / "mathjax").mkdir(parents=True)
    (tmp_path / "fig.png").write_bytes(b"\x89PNG")
    write(tmp_path, "other.html", "")
    write(tmp_path, "page.html", '<img src="fig.png"><a href="other.html#x">x</a>'
          '<script src="_static/mathjax/tex-svg-full.js"></script>')
    assert check(tmp_path) == []


def test_problems_are_reported(tmp_path):
    (tmp_path / "empty.png").write_bytes(b"")
    write(tmp_path, "gkyp_lemma.html",
          '<img src="empty.png"><a href="missing.html">x</a>'
          '<script src="https://cdn.example.org/mathjax.js"></script>')
    found = "\n".join(check(tmp_path))
    assert "missing or empty image empty.png" in found
    assert "broken link missing.html" in found
    assert "from the web" in found
    assert "does not load the book's own MathJax" in found
