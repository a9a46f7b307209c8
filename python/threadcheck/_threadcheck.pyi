"""The compiled half of the package (see ``threadcheck/__init__.py``)."""

from typing import Tuple

__version__: str

def run(command: str, document: str, args: str) -> Tuple[str, bool]:
    """Runs ``command`` on ``args`` (a JSON object of its keyword arguments) and returns
    ``document`` (``json``, ``text``, ``svg``, ``html``, ``fix``) and whether the job passed."""
    ...
