"""The compiled half of the package (see ``threadcheck/__init__.py``)."""

from typing import List, Tuple

__version__: str

def run(command: str, document: str, args: str) -> Tuple[str, bool]:
    """Runs ``command`` on ``args`` (a JSON object of its keyword arguments) and returns
    ``document`` (``json``, ``text``, ``svg``, ``html``, ``fix``) and whether the job passed."""
    ...

def write_files(files: List[Tuple[str, str]]) -> None:
    """Writes each (path, text) as the command line writes its outputs: none that the last
    ``run`` read or that shares a file with another, all or none, atomically; devices and FIFOs
    in place, links followed, modes kept. Raises ``ValueError`` with the one-line message."""
    ...

def keys(command: str) -> List[str]:
    """The keyword arguments ``command`` takes: the fields the command line's flags and the
    API's keys are read into. Raises ``ValueError`` for a command the API does not run."""
    ...
