"""The instructor's studio: a local web app to draw a mechanism and see its plans live.

``planmethod studio`` (:mod:`planmethod.studio.command`) serves one page and a JSON API on
127.0.0.1 only:

* :mod:`planmethod.studio.api` — what the page asks for, as functions of plain data: solve an
  exercise written as drawn (the report of ``planmethod solve --json`` with the plans' SVG),
  open and save files under the studio's folder, turn the crank, draw variants from a template
  made of the drawing, export LMS packages;
* :mod:`planmethod.studio.server` — the HTTP server (the standard library's
  ``ThreadingHTTPServer``) with its safety rules: a token per start, loopback ``Host`` and
  same-site ``Origin`` only, bounded bodies, paths only under the folder;
* ``studio.html`` — the page (HTML, CSS and script in one file, package data). It draws what
  the instructor draws (points, links, pairs on a grid) and shows what the server computed;
  it computes no mechanics.

Nothing here is imported by ``import planmethod``.
"""
