"""The lean core and the extras: ``import leuven_rt`` loads no scipy, matplotlib or tqdm; the
public face works without them; a room that needs an extra names it; the version is one."""

from __future__ import annotations

import importlib.metadata
import subprocess
import sys
import textwrap

import pytest

import leuven_rt
from leuven_rt import cli
from leuven_rt._extras import MissingExtraError, require

# Hides scipy, matplotlib and tqdm from the import system, as in an install without extras.
HIDE = """
import sys
class Hide:
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in {"scipy", "matplotlib", "tqdm"}:
            raise ModuleNotFoundError(f"No module named {name!r}", name=name)
        return None
sys.meta_path.insert(0, Hide())
"""


def run(code: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-c", HIDE + textwrap.dedent(code)], capture_output=True, text=True, timeout=120
    )


def test_import_loads_nothing_heavy() -> None:
    done = subprocess.run(
        [sys.executable, "-c", "import sys, leuven_rt; print(sorted(m for m in sys.modules "
         "if m.split('.')[0] in {'scipy', 'matplotlib', 'tqdm'}))"],
        capture_output=True, text=True, check=True, timeout=120,
    )  # fmt: skip
    assert done.stdout.strip() == "[]"


def test_public_face_works_without_the_extras() -> None:
    done = run(
        """
        import numpy as np, tempfile, os
        import leuven_rt as lr
        p = lr.Params(Fc=1.0, Fs=1.5, Vs=1e-3, delta=2.0, n=2.0, sigma1=30.0, sigma2=0.4,
                      W=[0.6, 0.5, 0.4, 0.3], Delta=[1e-6, 2e-6, 4e-6, 8e-6])
        path = os.path.join(tempfile.mkdtemp(), "params.json")
        p.save(path)
        p = lr.Params.load(path)
        model = lr.ModelFile(friction=p, level=lr.PositionLevel(trend=(0.1, 0.0)), offset=0.2)
        model.save(path + ".model.json")
        assert lr.ModelFile.load(path + ".model.json") == model and lr.ModelFile.load(path).friction == p
        v = 1e-3 * np.sin(np.linspace(0, 6, 500))
        f = lr.simulate(p, v, 1e-3)
        model = lr.LeuvenModel(p)
        c = lr.Compensator(p, 1e-3, mode="feedforward")
        forces = [c.step(x) for x in v[:50]]
        lr.MassSystem(p, mass=1.0).run(np.zeros(100), 1e-3)
        online = lr.OnlineIdentifier(p.Delta)
        online.run(np.zeros(10), v[:10], f[:10])
        assert np.all(np.isfinite(f)) and all(np.isfinite(forces))
        assert not {m.split(".")[0] for m in sys.modules} & {"scipy", "matplotlib", "tqdm"}
        print("ok")
        """
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "ok"


@pytest.mark.parametrize(
    ("module", "extra"),
    [
        ("leuven_rt.fitting.select", "analysis"),
        ("leuven_rt.discrepancy", "analysis"),
        ("leuven_rt.data", "analysis"),
        ("leuven_rt.prediction", "analysis"),
        ("leuven_rt.reference", "analysis"),
        ("leuven_rt._plot", "plot"),
    ],
)
def test_a_missing_extra_is_named(module: str, extra: str) -> None:
    done = run(
        f"""
        import leuven_rt
        try:
            import {module}
        except ImportError as error:
            print(type(error).__name__, error)
        """
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("MissingExtraError")
    assert f"install leuven-rt[{extra}]" in done.stdout


def test_require() -> None:
    require("numpy", extra="analysis")
    with pytest.raises(ImportError, match=r"install leuven-rt\[analysis\]") as raised:
        require("numpy", "no_such_package_here", extra="analysis", needed_by="a test")
    assert isinstance(raised.value, MissingExtraError)
    assert raised.value.extra == "analysis"


def test_one_version(capsys: pytest.CaptureFixture[str]) -> None:
    assert leuven_rt.__version__ == importlib.metadata.version("leuven-rt")
    with pytest.raises(SystemExit) as exited:
        cli.main(["--version"])
    assert exited.value.code == 0
    assert capsys.readouterr().out.strip() == f"leuven-rt {leuven_rt.__version__}"
