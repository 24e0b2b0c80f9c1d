"""Tables of the report as standalone HTML pages (Snakemake's report shows HTML results inline and
offers other formats, CSV included, only for download)."""
from __future__ import annotations

import html
from pathlib import Path

import pandas as pd

STYLE = ("body{font-family:sans-serif;font-size:13px;margin:12px}"
         "table{border-collapse:collapse}th,td{border:1px solid #bbb;padding:3px 7px;text-align:right}"
         "th{background:#eee}td.text{text-align:left;max-width:42em}p.note{max-width:60em;color:#333}")


def html_table(df: pd.DataFrame, title: str, notes=(), digits: int = 4) -> str:
    """``df`` as an HTML page: title, the table (floats to ``digits`` significant digits, text
    columns left-aligned) and one paragraph per note."""
    def cell(v):
        if isinstance(v, float):
            return "" if pd.isna(v) else f"{v:.{digits}g}"
        return html.escape(str(v))

    head = "".join(f"<th>{html.escape(str(c))}</th>" for c in df.columns)
    rows = []
    for _, r in df.iterrows():
        tds = "".join(f'<td class="text">{cell(v)}</td>' if isinstance(v, str) else f"<td>{cell(v)}</td>"
                      for v in r.values)
        rows.append(f"<tr>{tds}</tr>")
    body = "".join(f'<p class="note">{html.escape(n)}</p>' for n in notes)
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title>"
            f"<style>{STYLE}</style></head><body><h3>{html.escape(title)}</h3>"
            f"<table><tr>{head}</tr>{''.join(rows)}</table>{body}</body></html>")


def write_html_table(df: pd.DataFrame, path, title: str, notes=(), digits: int = 4) -> None:
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text(html_table(df, title, notes, digits))
