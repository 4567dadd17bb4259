"""Layout of power-flow diagrams: what a diagram shows and where everything goes.

Pure computation (numpy and networkx, no matplotlib), so the layout can be tested and
reused without a drawing backend; :mod:`powergraph.plot.power_flow` draws it.

- :mod:`powergraph.plot.layout.view`: :class:`~powergraph.plot.layout.view.FlowView`,
  the drawing-independent content of one diagram (flows seen from a frame, labels);
- :mod:`powergraph.plot.layout.layout`: :func:`~powergraph.plot.layout.layout.layout_flow`,
  a layered layout that follows the power;
- :mod:`powergraph.plot.layout.place`: rows, arrow routes and label spots;
- :mod:`powergraph.plot.layout.fold`: long diagrams folded onto bands near 16 : 9;
- :mod:`powergraph.plot.layout.parts`: the records both build (``LayoutStyle``,
  ``NodePlace``, ``EdgeRoute``, ``FlowLayout``, ``Skeleton``);
- :mod:`powergraph.plot.layout.geometry`: boxes, Bézier routes, text-size estimates.

Examples
--------
>>> from powergraph.plot.layout.view import format_power
>>> format_power(2270.0)
'2.27 kW'
"""
