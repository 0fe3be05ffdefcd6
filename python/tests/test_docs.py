"""The code blocks of docs/python.md run, in order, in one namespace, from the repository's
root (as the page says), and make the pictures they promise."""

import os
import re

import pytest

from conftest import ROOT

PAGE = ROOT / "docs/python.md"


def blocks():
    return re.findall(r"^```python\n(.*?)^```", PAGE.read_text(), flags=re.M | re.S)


def test_the_page_has_its_tour():
    assert len(blocks()) >= 3


def test_the_code_blocks_run(monkeypatch):
    pytest.importorskip("matplotlib")
    monkeypatch.chdir(ROOT)
    (ROOT / "out").mkdir(exist_ok=True)
    for picture in ("mug.png", "mug-a1.png"):
        (ROOT / "out" / picture).unlink(missing_ok=True)
    namespace = {"__name__": "docs_python"}
    for number, code in enumerate(blocks(), 1):
        exec(compile(code, f"{PAGE.name} block {number}", "exec"), namespace)
    for picture in ("mug.png", "mug-a1.png"):
        assert os.path.getsize(ROOT / "out" / picture) > 10000
