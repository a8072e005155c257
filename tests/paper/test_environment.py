"""Tests of fdsc.paper.shared.environment."""

from fdsc.paper.shared.environment import build_commit, environment


def test_environment_lists_python_and_packages():
    env = environment()
    assert env["python"].count(".") >= 1
    assert "numpy" in env["packages"] and env["packages"]["numpy"]


def test_build_commit_of_this_checkout():
    commit = build_commit()
    if commit != "not a git checkout":
        head = commit.split()[0]
        assert len(head) == 40 and all(c in "0123456789abcdef" for c in head)


def test_build_commit_outside_a_repository(tmp_path):
    assert build_commit(tmp_path) == "not a git checkout"


def test_build_commit_without_git(monkeypatch, tmp_path):
    monkeypatch.setenv("PATH", str(tmp_path))
    assert build_commit() == "not a git checkout"
