"""The package itself: its version, its type stubs and docstrings, the
command line, and the README's example."""

import ast
import re
import subprocess
import sys
import types
from pathlib import Path

import hooke

ROOT = Path(__file__).resolve().parents[4]


def test_the_version_is_the_workspaces():
    manifest = (ROOT / "Cargo.toml").read_text()
    version = re.search(r'\[workspace\.package\]\nversion = "([^"]+)"', manifest).group(1)
    assert hooke.__version__ == version


def stubs():
    """The stub file's names: module-level ones, and each class's members."""
    tree = ast.parse((Path(hooke.__file__).parent / "_hooke.pyi").read_text())
    names, members = set(), {}
    for node in tree.body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            names.add(node.name)
        if isinstance(node, (ast.AnnAssign,)):
            names.add(node.target.id)
        if isinstance(node, ast.ClassDef):
            members[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
    return names, members


def test_every_name_has_a_stub_and_a_docstring():
    names, members = stubs()
    assert (Path(hooke.__file__).parent / "py.typed").exists()
    for name in hooke.__all__:
        assert name in names, name
        if name == "__version__":
            continue
        value = getattr(hooke, name)
        assert value.__doc__ and value.__doc__.strip(), name
        if isinstance(value, type) and not issubclass(value, BaseException):
            public = {m for m in vars(value) if not m.startswith("_")}
            assert public <= members[name], public - members[name]
            for member in public:
                assert getattr(value, member).__doc__, f"{name}.{member}"


def test_python_m_hooke_is_the_command_line():
    done = subprocess.run([sys.executable, "-m", "hooke", "scenes"], capture_output=True, text=True)
    assert done.returncode == 0
    assert done.stdout.splitlines()[0].startswith("stiff-cloth")
    assert set(hooke.builtin_scenes()) == {line.split()[0] for line in done.stdout.splitlines()}
    bad = subprocess.run([sys.executable, "-m", "hooke", "run", "--builtin", "nope"],
                         capture_output=True, text=True)
    assert bad.returncode == 1 and 'no built-in scene "nope"' in bad.stderr


def test_the_readmes_example_runs(monkeypatch, tmp_path):
    readme = (ROOT / "README.md").read_text()
    section = readme[readme.index("## Python"):]
    example = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    assert len(example.strip().splitlines()) <= 12
    curves = []
    pyplot = types.ModuleType("matplotlib.pyplot")
    pyplot.plot = lambda x, y, **kw: curves.append((list(x), list(y), kw))
    pyplot.legend = pyplot.xlabel = pyplot.ylabel = pyplot.show = lambda *a, **k: None
    pyplot.savefig = lambda *a, **k: None
    matplotlib = types.ModuleType("matplotlib")
    matplotlib.pyplot = pyplot
    monkeypatch.setitem(sys.modules, "matplotlib", matplotlib)
    monkeypatch.setitem(sys.modules, "matplotlib.pyplot", pyplot)
    monkeypatch.chdir(tmp_path)
    exec(compile(example, "README.md", "exec"), {})
    assert len(curves) >= 3
    for times, energies, _ in curves:
        assert len(times) == len(energies) > 10
