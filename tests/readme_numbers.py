"""Run the README's "Use it on your own plant" example and print its numbers in full (JSON).

Usage: ``python tests/readme_numbers.py README.md OUT.json``, from any folder (the example's
figure is written to the current folder).

``.ci/run`` runs it with the editable install and with the installed wheel, in the same
machine with the same pinned packages, and compares the two outputs: a packaged install must
compute, from scratch, exactly the numbers of the tested tree (gains, certified gains, Theorem 1's
γ's, the energies of the switched and the fixed loops, the switch count), with its own compiled
kernels. It also prints where ``fdsc`` was imported from and the fingerprint of its sources and
data (:func:`fdsc.paper.shared.cache.fingerprint`), which the cached chapter results are keyed by.
"""

import contextlib
import io
import json
import re
import sys
from pathlib import Path


def example_code(readme):
    """The one python block of the README's "Use it on your own plant" section."""
    text = Path(readme).read_text(encoding="utf-8")
    section = text.split("## Use it on your own plant", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```python\n(.*?)```", section, re.S)
    if len(blocks) != 1:
        raise ValueError(f"{readme}: the section must hold exactly one python example, found {len(blocks)}")
    return blocks[0]


def numbers(readme):
    """Run the example; return its printed text and its numbers at full precision."""
    import matplotlib

    matplotlib.use("Agg")
    import fdsc
    from fdsc.paper.shared.cache import fingerprint

    ns = {}
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(example_code(readme), "README.md", "exec"), ns)  # noqa: S102
    ctrl, run = ns["ctrl"], ns["run"]
    fixed = [fdsc.simulate(ctrl.mode(i), ns["d"], ns["t"]).energy() for i in range(ctrl.n_modes)]
    return {"fdsc": fdsc.__file__, "fingerprint": fingerprint(), "printed": out.getvalue(),
            "gains": [r.K.tolist() for r in ctrl.synthesis],
            "gamma_sweep": [float(r.gamma_sweep) for r in ctrl.synthesis],
            "gamma_lmi": [float(r.gamma_lmi) for r in ctrl.synthesis],
            "theorem1_gammas": ctrl.gammas.tolist(),
            "energy_fdsc": float(run.energy()), "energy_fixed": [float(e) for e in fixed],
            "switches": int((run.sigma[1:] != run.sigma[:-1]).sum())}


if __name__ == "__main__":
    if len(sys.argv) != 3:
        raise SystemExit("usage: python tests/readme_numbers.py README.md OUT.json")
    result = numbers(sys.argv[1])
    Path(sys.argv[2]).write_text(json.dumps(result, indent=1) + "\n", encoding="utf-8")
    print(f"{result['fdsc']}: FDSC energy {result['energy_fdsc']!r}, {result['switches']} switches")
