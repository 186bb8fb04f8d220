"""Formatting shared by the report's sections (bench/report.py and the modules beside it)."""

from __future__ import annotations

from typing import List, Optional


def table(header: List[str], rows: List[List[str]]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(row) + " |" for row in rows]
    return "\n".join(lines)


def fmt_time(us: Optional[float]) -> str:
    if us is None:
        return "n/a"
    if us >= 1e6:
        return f"{us / 1e6:.2f} s"
    if us >= 1e3:
        return f"{us / 1e3:.3g} ms"
    return f"{us:.3g} µs"


def fmt_err(e: float) -> str:
    return "0" if e == 0 else f"{e:.1e}"


def machine_line(data: dict) -> str:
    """One line on where and how a results file was made (bench/record.py's header)."""
    m = data.get("machine", {})
    load = " / ".join(", ".join(f"{x:.2f}" for x in m[k])
                      for k in ("load_average_start", "load_average_end") if m.get(k))
    versions = ", ".join(f"{k} {v}" for k, v in m.get("versions", {}).items())
    return (f"`{data.get('command', '?')}` on {m.get('cpu', '?')} ({m.get('cores', '?')} cores), "
            f"{m.get('date', '?')}; load average at start / end: {load or 'not recorded'}"
            + (f"; {versions}" if versions else "") + ".")
