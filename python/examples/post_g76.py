"""A post-processor's last step, in the style of a FreeCAD or LinuxCNC post: before a threading
cycle is written out, threadcheck cuts it in the computer; when the pitch diameter is off, the
final X is moved to the middle of the tolerance and checked again.

Run: ``python post_g76.py M20x1.5-6g 18.2`` prints the program and what was checked.
"""

from __future__ import annotations

import sys
from typing import List, Tuple

import threadcheck


def g76_program(x_final: float, z_end: float = -20.0, pitch: float = 1.5) -> str:
    """A two-block Fanuc G76 for an external metric thread, from X24 at Z5 (thread height
    0.9 mm as P900, first depth 0.2 mm as Q200)."""
    return (
        "%\nO0100 (POST OUTPUT)\nG21 G97 S500 M3\nT0101\nG0 X24.0 Z5.0\n"
        "G76 P010060 Q100 R0.02\n"
        f"G76 X{x_final:.3f} Z{z_end:.1f} P900 Q200 F{pitch}\n"
        "G0 X100.0 Z100.0\nM30\n%\n"
    )


def checked_program(designation: str, x_final: float, insert: str = "full") -> Tuple[str, List[str]]:
    """The program, its X corrected when threadcheck finds d2 off; and what was done."""
    log: List[str] = []
    report = threadcheck.verify(designation, program=g76_program(x_final), insert=insert,
                                program_name="post.nc", dialect="fanuc")
    operation = report["operations"][0]
    log.append(f"X{x_final:.3f}: {report['verdict']}")
    if report["verdict"] != "pass":
        suggested = operation["suggested_final_x"]
        if suggested is None:
            raise ValueError("threadcheck offers no X: " + str(operation.get("reason", "starts are wrong")))
        x_final = round(suggested, 3)
        again = threadcheck.verify(designation, program=g76_program(x_final), insert=insert,
                                   program_name="post.nc", dialect="fanuc")
        log.append(f"X{x_final:.3f}: {again['verdict']} (suggested by threadcheck)")
    return g76_program(x_final), log


def main(argv: List[str]) -> int:
    designation = argv[1] if len(argv) > 1 else "M20x1.5-6g"
    x_final = float(argv[2]) if len(argv) > 2 else 18.2
    program, log = checked_program(designation, x_final)
    sys.stdout.write(program)
    for line in log:
        sys.stderr.write(line + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
