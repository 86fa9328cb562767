"""The five-line Python example at the top of README.md runs as printed."""
import re

import matplotlib

matplotlib.use("Agg")

from conftest import ROOT  # noqa: E402


def test_readme_python_example_runs(tmp_path, monkeypatch, capsys):
    text = (ROOT / "README.md").read_text()
    code = re.search(r"```python\n(.*?)```", text, re.S).group(1)
    assert len(code.strip().splitlines()) == 5
    monkeypatch.chdir(tmp_path)
    code = code.replace('"examples/', f'"{ROOT}/examples/')
    exec(compile(code, "README.md", "exec"), {})
    out = capsys.readouterr().out
    assert "t = 0.10 s, E = 1156" in out and re.search(r"\(820, 2\) [0-9a-f]{16}", out), out
    assert (tmp_path / "slide.png").stat().st_size > 10000
