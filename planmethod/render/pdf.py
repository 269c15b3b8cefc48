"""SVG pages joined into one PDF, at their true size, with their fonts embedded.

Each page is an SVG whose ``width`` and ``height`` are in millimetres (the booklet's A4 pages):
CairoSVG draws it onto one page of a single cairo PDF surface of that size, so a millimetre of
the SVG is a millimetre on paper printed at 100 %, and cairo embeds (a subset of) every font
the text uses. Needs CairoSVG (the ``png`` and ``paper`` extras).

Examples
--------
>>> from planmethod.render.canvas import Canvas
>>> canvas = Canvas()
>>> canvas.rectangle((10, 10), (50, 20), fill="#000000")
>>> page = canvas.svg("a page", view=(0, 0, 210, 297), unit="mm").svg
>>> pdf = pdf_pages([page, page])  # doctest: +SKIP
>>> pdf[:5]  # doctest: +SKIP
b'%PDF-'
"""

from __future__ import annotations

import io
from collections.abc import Iterable

__all__ = ["pdf_pages"]

#: points (1/72 in) per CSS pixel (1/96 in), the unit CairoSVG lays pages out in
_POINTS_PER_PX = 72.0 / 96.0


def pdf_pages(pages: Iterable[str], *, title: str = "") -> bytes:
    """The SVG ``pages`` as one PDF, page after page, each at its own size.

    Raises
    ------
    ValueError
        If a page has no size.
    """
    import cairocffi
    from cairosvg.parser import Tree
    from cairosvg.surface import PDFSurface

    output = io.BytesIO()
    shared = cairocffi.PDFSurface(output, 1, 1)
    if title:
        shared.set_metadata(cairocffi.PDF_METADATA_TITLE, title)
    # a fixed date: the same pages make the same bytes
    shared.set_metadata(cairocffi.PDF_METADATA_CREATE_DATE, "2026-01-01T00:00:00Z")

    class _Page(PDFSurface):
        """CairoSVG's PDF surface drawing onto the next page of ``shared``."""

        def _create_surface(self, width: float, height: float):
            shared.set_size(width, height)
            return shared, width, height

    for svg in pages:
        page = _Page(Tree(bytestring=svg.encode("utf-8")), None, 96)
        page.context.show_page()
    shared.finish()
    return output.getvalue()
