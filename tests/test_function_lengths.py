"""The function-length check of `make lint` (tools.function_lengths) on sources of known lengths: every
function over the limit is listed by module:function with its line count (methods, nested and async
functions, decorators not counted), none at the limit, and the exit status says whether any was found."""

from tools.function_lengths import main, offenders


def body(n_lines: int, indent: str = "    ") -> str:
    """A function body of ``n_lines`` lines (the def line excluded)."""
    return "".join(f"{indent}x{i} = {i}\n" for i in range(n_lines))


def write_package(root):
    pkg = root / "pkg"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "__init__.py").write_text("@staticmethod\n@property\ndef at_limit():\n" + body(79))
    (pkg / "sub" / "mod.py").write_text(
        "def long_one():\n" + body(85)
        + "\nclass Thing:\n    async def method(self):\n" + body(81, " " * 8)
        + "\ndef outer():\n    def inner():\n" + body(90, " " * 8) + "    return inner\n")


def test_every_offender_is_listed_with_its_length(tmp_path):
    write_package(tmp_path)
    assert offenders(["pkg"], tmp_path) == [
        ("pkg.sub.mod:long_one", 86), ("pkg.sub.mod:Thing.method", 82),
        ("pkg.sub.mod:outer", 93), ("pkg.sub.mod:outer.inner", 91)]
    assert offenders(["pkg"], tmp_path, max_lines=91) == [("pkg.sub.mod:outer", 93)]


def test_exit_status_and_report(tmp_path, monkeypatch, capsys):
    write_package(tmp_path)
    monkeypatch.chdir(tmp_path)
    assert main(["pkg", "--max-lines", "100"]) == 0
    assert main(["pkg"]) == 1
    out = capsys.readouterr().out
    assert "pkg.sub.mod:long_one  86 lines" in out and "at_limit" not in out
    (tmp_path / "pkg" / "short.py").write_text("def f():\n    return 1\n")
    assert offenders(["pkg"], tmp_path, max_lines=1)[:2] == [("pkg:at_limit", 80), ("pkg.short:f", 2)]
