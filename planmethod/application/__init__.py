"""The application layer: what a person asks planmethod to do, as use cases with typed
requests and results, between the results (report, figures, grading) and the surfaces that
call them (the command line, the studio, a notebook or a script).

* :mod:`~planmethod.application.api` — the Python API: ``planmethod.load(path)`` →
  :class:`~planmethod.application.api.Exercise`, ``.solve(angle)`` →
  :class:`~planmethod.application.api.Solution` (``.plans``, ``.svg()``, ``.report()``,
  ``.as_dict()``), ``.grade(answers)``, ``.workbook()``, ``.variants()``;
* :mod:`~planmethod.application.solving` — solve an exercise at a crank angle: the analysis,
  its figures and its report as a course prints it;
* :mod:`~planmethod.application.sweeping` — the full turn: its table, CSV and plot;
* :mod:`~planmethod.application.workbook` — build a workbook page (its frames solved in a
  bounded pool of processes: :mod:`~planmethod.application.workers`);
* :mod:`~planmethod.application.templates` — make a template of a drawn mechanism;
* :mod:`~planmethod.application.variants` — draw variants and the files of a course folder;
* :mod:`~planmethod.application.exporting` — export a class to an LMS, or a whole teaching
  run;
* :mod:`~planmethod.application.grading` — grade answers and drawings;
* :mod:`~planmethod.application.checking` — check a table of coordinates;
* :mod:`~planmethod.application.studying` and :mod:`~planmethod.application.animating` —
  the parameter study and the animation;
* :mod:`~planmethod.application.language` — which language a run speaks;
* :mod:`~planmethod.application.tasks` — how a long use case tells its progress and is
  cancelled.

The limits a use case keeps (:data:`~planmethod.application.variants.MAX_VARIANTS`, the
finest workbook step…) live here too, so that the command line and the studio keep the same
ones. Neither surface imports the other; both import this layer.

Nothing here is imported by ``import planmethod``: the top level reaches the API lazily.
"""
