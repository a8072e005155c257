import shutil
from pathlib import Path

import pytest
from check_book_html import MAX_TEX_REPORTS, check, raw_tex_snippets, visible_text

#: What Jupyter Book 1 writes for display maths inside a list item and a paragraph and for a
#: bibliography title with maths (provenance in the file's opening comment).
SPHINX_PAGE = Path(__file__).resolve().parent / "fixtures" / "raw_tex_page.html"
SMALLMATRIX = r"\left[\begin{smallmatrix}a\end{smallmatrix}\right]"
#: Text long enough to keep two findings in separate snippets.
FILLER = "The band LMI is solved once for every frequency range of the aircraft model."


def write(tmp_path, name, body, head=""):
    (tmp_path / name).write_text(f"<html><head>{head}</head><body>{body}</body></html>",
                                 encoding="utf-8")


def tex_problems(tmp_path):
    return [p for p in check(tmp_path) if "raw TeX" in p]


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


def test_emoji_in_visible_text_are_reported_arrows_and_code_are_not(tmp_path):
    # MyST-NB's execution table once showed ✅ in its Status column (book/_ext/offline.py now
    # writes "ok"); a machine without an emoji font draws it as an empty box
    write(tmp_path, "environment.html", "<table><tr><td>baselines</td><td>✅</td></tr>"
          "<tr><td>x</td><td>❌</td></tr></table><p>A → B ⇒ C ≤ D</p><pre>print('🙂')</pre>")
    write(tmp_path, "clean.html", "<p>A → B ⇒ C ≤ D, σ ∈ {1, 2}</p><code>✅</code>")
    found = check(tmp_path)
    assert found == ["environment.html: emoji or pictographs in visible text (no font may draw "
                     "them): ✅ ❌"]


def test_raw_tex_in_paragraph_list_item_and_citation_is_reported(tmp_path):
    write(tmp_path, "page.html",
          f"<p>{FILLER} with slack $${SMALLMATRIX}$$ in the paragraph. {FILLER}</p>"
          f"<ol><li><p>{FILLER} The list item has $${SMALLMATRIX}$$ too.</p></li></ol>"
          f'<div class="citation"><p>{FILLER} D. Ye. Reliable $H_\\infty $ control. 2004.</p></div>')
    found = check(tmp_path)
    assert len(found) == 3, found
    assert all(p.startswith("page.html: raw TeX in visible text: '") for p in found)
    assert r"with slack $$\left[\begin{smallm" in found[0]
    assert r"The list item has $$\left[\begin{smallm" in found[1]
    assert r"Reliable $H_\infty $ control. 2004.'" in found[2]


def test_typeset_maths_code_and_metadata_are_not_reported(tmp_path):
    write(tmp_path, "page.html",
          f'<p>Inline <span class="math notranslate nohighlight">\\({SMALLMATRIX}\\)</span>, '
          "costs $5 or $3, a lone $ sign.</p>"
          f'<div class="math notranslate nohighlight"><span class="eqno">(1)</span>'
          f"\\[{SMALLMATRIX} \\frac{{1}}{{2}}\\]</div>"
          '<div class="citation"><p>Reliable <span class="math">\\(H_\\infty\\)</span> control.</p>'
          '<a href="#c" title="Reliable $H_\\infty $ control">[1]</a></div>'
          "<pre>$ pip install fdsc  # $x_1$ \\alpha</pre>"
          '<div class="highlight-bash notranslate"><div class="highlight"><pre><span>$</span> '
          "echo $HOME_DIR $$</pre></div></div>"
          '<div class="cell_input"><div>print(r"$\\sigma_1$")</div></div>'
          "<p>Run <code>$$\\frac{a}{b}$$</code>, press <kbd>\\left</kbd>; "
          "<samp>$x_1$</samp> <tt>\\begin</tt></p>"
          "<noscript>\\begin{x}</noscript><style>p::before { content: '$$' }</style>"
          '<script>const s = "$x_1$ \\\\frac";</script><mjx-container>\\frac</mjx-container>'
          '<math><mi>\\sigma</mi></math><span class="MathJax">$$</span>',
          head="<title>$H_\\infty$ \\frac{a}{b}</title>")
    assert check(tmp_path) == []


@pytest.mark.parametrize("tex", ["$$x = 1$$", "$ $", r"\begin{bmatrix}", r"\end{bmatrix}",
                                 r"\left(", r"\right)", r"\frac{1}{2}", r"\mathbf{x}", r"\sigma",
                                 r"\operatorname{He}", r"\(x\)", r"\[x\]", "$x_1$", "$x^2$",
                                 r"$H_\infty $", "$A_K^{-1}$", r"$\gamma$"])
def test_each_raw_tex_pattern_is_reported(tmp_path, tex):
    write(tmp_path, "page.html", f"<p>The bound {tex} holds.</p>")
    assert tex_problems(tmp_path) == [f"page.html: raw TeX in visible text: 'The bound {tex} holds.'"]


@pytest.mark.parametrize("prose", ["costs $5 or $3", "a lone $ sign", "US$ 40 and $ 30_000 $",
                                   "$x$ has no TeX command", "snake_case and x^2 outside dollars",
                                   r"the escape \n in prose", "a $ ends a line,\nand $x_1 starts the next",
                                   "$" + "x_1 " * 30 + "$ is too long for inline maths"])
def test_prose_with_dollars_is_not_reported(tmp_path, prose):
    write(tmp_path, "page.html", f"<p>{prose}</p>")
    assert tex_problems(tmp_path) == []


def test_only_the_first_findings_of_a_page_are_listed(tmp_path):
    write(tmp_path, "page.html", "".join(f"<p>{FILLER} \\sigma_{i}</p>" for i in range(5)))
    found = tex_problems(tmp_path)
    assert len(found) == MAX_TEX_REPORTS + 1
    assert found[-1] == f"page.html: raw TeX in visible text: {5 - MAX_TEX_REPORTS} more"


def test_visible_text_drops_typeset_maths_and_separates_blocks():
    html = ('<p>matrix\n$<span class="math notranslate nohighlight">\\(\\Theta\\)</span>$\nis</p>'
            "<ul><li>one<br>two<img src='x.png'></li><li>three</ul><p>four</span>five</p>"
            "<pre>code</pre>six")
    lines = [line for line in visible_text(html).split("\n") if line]
    assert lines == ["matrix", "$$", "is", "one", "two", "three", "fourfive", "six"]


def test_page_built_by_sphinx_with_display_maths_in_prose_is_reported(tmp_path):
    shutil.copy(SPHINX_PAGE, tmp_path / "defect.html")
    found = [p for p in check(tmp_path) if "visible code" not in p]   # (the fixture shows code)
    assert len(found) == 3, found
    assert all(p.startswith("defect.html: raw TeX in visible text: '") for p in found)
    # the list item: $<span class="math">...</span>$
    assert "quadratic form with matrix $$ is negative on the subspace" in found[0]
    # the paragraph: dollars paired across the two $$ leave TeX outside any maths element
    assert r"\left[\begin{smallmatrix}" in found[1]
    # the bibliography entry (sphinxcontrib-bibtex keeps the title's TeX as text)
    assert r"Reliable $H_\infty $ control" in found[2]


def test_sphinx_page_finds_no_tex_in_typeset_maths_or_code():
    text = visible_text(SPHINX_PAGE.read_text(encoding="utf-8"))
    for typeset_or_code in ("a_1", "x = ", "pip install", "cell output", "$HOME", "Defect &"):
        assert typeset_or_code not in text
    assert len(raw_tex_snippets(text)) == 3


READERS_PAGE = Path(__file__).resolve().parent / "fixtures" / "readers_page.html"


def test_visible_code_share_counts_only_code_not_folded_away():
    from check_book_html import code_share

    html = READERS_PAGE.read_text(encoding="utf-8")
    # the folded cell's words do not count; the shown cell's do
    share = code_share(html)
    shown = len("shown = one + two + three + four + five + six + seven + eight + nine + ten + eleven "
                "+ twelve".split())
    assert share == pytest.approx(shown / (shown + len(visible_text(html).split())))
    cell = '<div class="cell docutils container">\n'
    folded = html.replace(cell + '<div class="cell_input',
                          cell + '<details class="hide"><div class="cell_input')
    folded = folded.replace("twelve</pre>\n</div></div></div></div>",
                            "twelve</pre>\n</div></div></div></details></div>")
    assert code_share(folded) == 0.0


def test_project_speak_is_reported_with_what_it_is():
    from check_book_html import project_speak

    text = visible_text(READERS_PAGE.read_text(encoding="utf-8"))
    found = [what for what, _ in project_speak(text, "stationary.html")]
    assert found == ["an issue number", "a test path", "'record entry'", "a raw NumPy array",
                     "a record-entry id"]
    # the report's tables list the ids by design; paper symbols (K_f1, Q_1) are never reported
    assert "a record-entry id" not in [w for w, _ in project_speak(text, "report.html")]
    assert project_speak("the gains K_f1 and K_f3 and the weights Q_1, Q_2", "x.html") == []


def test_readers_pages_are_checked_in_the_build(tmp_path):
    shutil.copy(READERS_PAGE, tmp_path / "stationary.html")
    words = " ".join(["word"] * 1600)
    write(tmp_path, "intro.html", f"<article><h1>Title</h1><h2>Does FDSC work, and when?</h2><p>{words}</p>"
                                  "<h2>The book</h2></article>")
    write(tmp_path, "own_plant.html",
          '<div class="cell_input"><pre>' + "x = 1\n" * 50 + "</pre></div><p>a</p>")
    found = "\n".join(check(tmp_path))
    assert "stationary.html: visible code is" in found
    assert "stationary.html: an issue number in the prose" in found
    assert "intro.html: 1608 words of visible text, at most 1200" in found
    assert "own_plant.html" not in found          # the worked example may show its code
    write(tmp_path, "intro.html", "<h1>Title</h1><h2>Reading paths</h2><h2>Does FDSC work, and when?</h2>")
    found = "\n".join(check(tmp_path))
    assert "intro.html: its first section is not 'Does FDSC work, and when?'" in found


def test_the_consistency_checks_find_their_defects(tmp_path):
    from check_book_html import theorem1_certified, unlinked_terms

    write(tmp_path, "report.html", "<ol class='errata'><li>a</li><li>b</li></ol>")
    write(tmp_path, "intro.html", "<h2>Does FDSC work, and when?</h2><ol class='errata-short'><li>a</li></ol>"
                                  "<h2>The book</h2><p>the fixed controller chosen in advance</p>"
                                  "<p>(True, 3) and ['pc_pb_n_close', 'pc_x']</p>")
    found = "\n".join(check(tmp_path))
    assert "intro.html: 1 errata, the report lists 2" in found
    assert "intro.html: uses 'fixed controller chosen in advance' without linking it" in found
    assert "a Python tuple" in found and "a Python list of names" in found
    page = ('<a href="glossary.html#term-fixed-controller-chosen-in-advance">fixed controller chosen in '
            'advance</a>')
    assert unlinked_terms(page, "the fixed controller chosen in advance") == []
    assert theorem1_certified("The Q's, certified by Theorem 1's LMIs, hold.") != []


def test_the_report_is_short_and_its_tables_narrow_unless_folded(tmp_path):
    from check_book_html import MAX_CELL_CHARS, MAX_REPORT_WORDS, MAX_TABLE_COLUMNS, table_problems

    long_cell = "x " * MAX_CELL_CHARS
    wide = "<table><tr>" + "<td>a</td>" * (MAX_TABLE_COLUMNS + 1) + "</tr></table>"
    tall = f"<table><tr><th>a</th><td>{long_cell}</td></tr></table>"
    assert len(table_problems(wide)) == 1 and "columns" in table_problems(wide)[0]
    assert len(table_problems(tall)) == 1 and "characters" in table_problems(tall)[0]
    # folded away (a dropdown, a folded cell): not counted
    assert table_problems(f"<details><summary>more</summary>{wide}{tall}</details>") == []
    assert table_problems(f"<table><tr><td>short<details>{long_cell}</details></td></tr></table>") == []
    narrow = "<table><tr>" + "<td>a</td>" * MAX_TABLE_COLUMNS + "</tr></table>"
    assert table_problems(narrow) == []

    words = "word " * (MAX_REPORT_WORDS + 1)
    # the words, the erratum and the nine cells of the wide table
    write(tmp_path, "report.html", f"<ol class='errata'><li>a</li></ol><p>{words}</p>{wide}")
    found = "\n".join(check(tmp_path))
    assert f"report.html: {MAX_REPORT_WORDS + 11} words of unfolded visible text" in found
    assert "report.html: table 1 has 9 columns" in found
    write(tmp_path, "report.html", f"<ol class='errata'><li>a</li></ol><details><p>{words}</p></details>")
    assert not [p for p in check(tmp_path) if p.startswith("report.html")]


def test_errata_count_top_level_items_and_terms_count_only_the_article(tmp_path):
    # the report's items carry nested lists (the printed values); the landing page's list is flat
    write(tmp_path, "report.html", "<ol class='errata'><li id='erratum-1'>a <ul class='kv'><li>LF</li><li>HF</li>"
                                   "</ul></li><li id='erratum-2'>b</li></ol>")
    items = "".join(f"<li>{k} (<a href='report.html#erratum-{k}'>why</a>)</li>" for k in (1, 2))
    write(tmp_path, "intro.html", f"<h2>Does FDSC work, and when?</h2><ol class='errata-short'>{items}</ol>")
    assert not [p for p in check(tmp_path) if "errata" in p]
    write(tmp_path, "intro.html", "<h2>Does FDSC work, and when?</h2><ol class='errata-short'>"
                                  "<li>a (<a href='report.html#erratum-3'>why</a>)</li><li>b</li></ol>")
    found = "\n".join(check(tmp_path))
    assert "intro.html: the errata link to report.html#erratum-3, which has no such item" in found
    assert "intro.html: 1 errata do not link to their item in report.html" in found
    write(tmp_path, "intro.html", "<h2>Does FDSC work, and when?</h2><ol class='errata-short'><li>a</li></ol>")
    assert "intro.html: 1 errata, the report lists 2" in "\n".join(check(tmp_path))
    # a chapter title in the navigation is not the page's use of a term; the article's is
    nav = "<nav><a href='#ladder'>The non-causal limit and a predictive law</a></nav>"
    write(tmp_path, "baselines.html", f"{nav}<article class='bd-article'><p>Baselines.</p></article>")
    assert not [p for p in check(tmp_path) if p.startswith("baselines.html")]
    write(tmp_path, "baselines.html",
          f"{nav}<article class='bd-article'><p>the non-causal limit</p></article>")
    assert "baselines.html: uses 'non-causal limit' without linking" in "\n".join(check(tmp_path))
    # indices Sphinx generates list code names and terms by design
    write(tmp_path, "genindex.html", "<p>alpha_lf_in_hf (PiecewiseDominance property) non-causal limit</p>")
    assert not [p for p in check(tmp_path) if p.startswith("genindex.html")]


def test_a_myst_role_left_in_glued_markdown_is_reported(tmp_path):
    # glued Markdown is not parsed as MyST: a role in it reaches the reader as source
    write(tmp_path, "page.html", "<p>It is the {term}<code>optimal LTI controller</code> of the class, "
          "see {doc}<code>ladder</code>.</p><p>Sets {1, 2} and f{x} are fine.</p>")
    found = check(tmp_path)
    assert found == ["page.html: a MyST role reached the reader as source: '{term}'",
                     "page.html: a MyST role reached the reader as source: '{doc}'"]


def test_leaks_and_empty_headings_are_reported_where_the_build_shows_them(tmp_path):
    # a build folder beside its notebooks: book/_build/html, book/<stem>.ipynb
    html = tmp_path / "book" / "_build" / "html"
    html.mkdir(parents=True)
    (tmp_path / "book" / "switching_law.ipynb").write_text("{}")
    write(html, "page.html",
          "<article><section><h2>Bounds<a class=\"headerlink\">#</a></h2></section>"
          "<p>The least gamma squared is 9.932e+05 after 196254 steps (see switching_law).</p>"
          "<p>LF: w_l: 1 MF: w_1: 1</p><h3><a class=\"headerlink\">#</a></h3></article>")
    found = check(html)
    # the first findings of a page are listed (MAX_TEX_REPORTS), each kind found by leaks()
    assert any(p.startswith("page.html: e-notation in the prose:") and "9.932e+05" in p for p in found)
    from check_book_html import leaks, visible_text
    kinds = [w for w, _ in leaks(visible_text((html / "page.html").read_text()), "page.html", ["switching_law"])]
    assert list(dict.fromkeys(kinds)) == ["e-notation", "an integer of five or more digits without separators", "dictionary keys",
                     "a notebook file name"]
    assert "page.html: an empty heading or section: 'Bounds'" in found
    assert "page.html: an empty heading or section: ''" in found


def test_numbers_written_for_readers_are_not_leaks():
    from check_book_html import leaks
    text = ("Over 1,337 switches in 2023, commit 0394711, doi 10.5281/zenodo.7990805, ratio ×0.933 "
            "[0.857, 0.929]; the chapter on the switching law; 12:30; Note: the law; off the axes (above the "
            "median): aircraft: PassC-HF; generic: open loop; off the axes: aircraft: band-power law.")
    assert leaks(text, "page.html", ["switching_law"]) == []
    assert leaks("9.9e+05 and 123456", "references.html") == []


def test_a_number_typed_on_one_page_and_printed_on_another_is_reported(tmp_path):
    import json

    html = tmp_path / "book" / "_build" / "html"
    html.mkdir(parents=True)

    def notebook(stem, markdown, code=""):
        cells = [{"cell_type": "markdown", "source": [markdown], "metadata": {}}]
        if code:
            cells.append({"cell_type": "code", "source": [code], "metadata": {}, "outputs": [],
                          "execution_count": None})
        (tmp_path / "book" / f"{stem}.ipynb").write_text(json.dumps({"cells": cells}))

    # the band peak is glued on its home page; the landing page types it, another page types a
    # copy into the prose a code cell glues
    notebook("passive", "K_f3's HF peak is {glue:text}`peak`.")
    notebook("intro", "Its HF peak, 1.605, is the worst of the four (T = 500 s, h = 0.2, in 2013).")
    notebook("ladder", "The ladder.", code='glue("w", Markdown("a peak of 1.605 and ×1.00 by definition"))')
    notebook("changelog", "Version 0.2: the peak 1.605 was printed.")
    write(html, "passive.html",
          "<article><p>K_f3's HF peak is <span class='pasted-text'>1.605</span>.</p></article>")
    write(html, "intro.html", "<article><p>Its HF peak, 1.605, is the worst of the four.</p></article>")
    write(html, "ladder.html", "<article><p>a peak of 1.605 and ×1.00 by definition</p></article>")
    write(html, "changelog.html", "<article><p>Version 0.2: the peak 1.605 was printed.</p></article>")
    found = [p for p in check(html) if "is typed here" in p]
    assert found == ["intro: 1.605 is typed here and printed on changelog, ladder, passive: print it "
                     "from one computed value",
                     "ladder: 1.605 is typed here and printed on changelog, intro, passive: print it "
                     "from one computed value"]
    # once the landing page and the code print the glued value, nothing is reported
    notebook("intro", "Its HF peak, {glue:text}`peak`, is the worst of the four.")
    notebook("ladder", "The ladder.", code='glue("w", Markdown(f"a peak of {peak} and ×1.00 by definition"))')
    assert not [p for p in check(html) if "is typed here" in p]


def test_a_python_repr_in_a_cells_output_is_reported(tmp_path):
    # a cell whose last line returns a function shows its repr under the (hidden) code
    out = ('<div class="cell_output docutils container"><div class="output text_plain"><pre>'
           '&lt;function fdsc.paper.shared.plotting_axes.check_figures.&lt;locals&gt;.remove()&gt;</pre></div></div>')
    write(tmp_path, "page.html", f"<article><p>{FILLER}</p>{out}</article>")
    write(tmp_path, "ok.html", f"<article><p>{FILLER}</p><pre>x = 1  # a function of x</pre></article>")
    found = [p for p in check(tmp_path) if "repr" in p]
    assert found == ["page.html: a Python object's repr in a cell's output: "
                     "'&lt;function fdsc.paper.shared.plotting_axes.check_figures.'"]
