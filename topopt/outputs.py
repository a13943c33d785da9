"""What a finished design leaves in its output folder: result.json, the physical densities
(density.csv, rows from the top, as the image) and a picture (density.png, 8 pixels an element)."""
import json
import os
from pathlib import Path

import numpy as np


def _atomic_text(path: Path, text: str) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_text(text)
    os.replace(tmp, path)


def write_outputs(result, folder) -> list:
    """Write the files of ``result`` into ``folder``; return their names."""
    from matplotlib.image import imsave

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    image = result.problem.grid.image(result.density)
    _atomic_text(folder / "result.json", json.dumps(result.summary(), indent=1))
    rows = "\n".join(",".join(f"{v:.6g}" for v in row) for row in image)
    _atomic_text(folder / "density.csv", rows + "\n")
    tmp = folder / f".density.{os.getpid()}.png"
    imsave(tmp, np.kron(image, np.ones((8, 8))), cmap="gray_r", vmin=0.0, vmax=1.0, format="png")
    os.replace(tmp, folder / "density.png")
    return ["result.json", "density.csv", "density.png", "state.npz"]
