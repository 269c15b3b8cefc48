"""Rendering: SVG drawings of the plans (:mod:`.svg`, with shapely) and full-turn curves
(:mod:`.plots`, matplotlib). Nothing heavy is imported here: computation never needs it, and
``import planmethod`` imports neither svgwrite nor matplotlib nor shapely."""
