"""Plotting: the one layer that draws (after statics, methods and analyses; before cli).

Every plot function takes the result it draws and ``ax=None`` (a new figure from
:mod:`matplotlib.pyplot` when omitted), draws, returns the axes, and computes nothing:
the numbers come from the result.

- :mod:`powergraph.plot.power_flow`: power-flow diagrams of a solve (and of Wang 2021);
- :mod:`powergraph.plot.layout`: their layout, pure computation without matplotlib;
- :mod:`powergraph.plot.wang2021`: the paper's Figs. 12–13 (``FigureData``);
- :mod:`powergraph.plot.backlash`, :mod:`~powergraph.plot.cycloid`,
  :mod:`~powergraph.plot.volume`, :mod:`~powergraph.plot.sweep`,
  :mod:`~powergraph.plot.compare`: the analyses' figures;
- :mod:`powergraph.plot.text`, :mod:`~powergraph.plot.fonts`: every text they draw is
  plain (a name with ``$`` is drawn as written, never as mathtext), in fonts for any script.

No backend is chosen here or anywhere in the library: figures use the backend the user
chose (``MPLBACKEND``, ``matplotlib.use`` or the notebook's), so ``plt.show()`` works.
Only the command line, which writes files, selects a file backend.

Layering
--------
A module imports only from earlier layers at import time (errors/result → model →
kinematics → statics → methods, analyses → plot → cli). The **one exception** is the
``plot()`` method of every result (:class:`powergraph.result.Result`): it imports its
drawing function from this package *inside the method*, lazily, so results stay in their
own layer and importing them never imports matplotlib.

Examples
--------
>>> import powergraph as pg
>>> result = pg.solve(pg.load_model("models/rv40e_wang2021.yaml"))     # doctest: +SKIP
>>> ax = result.plot(frame="3")       # imports powergraph.plot.power_flow  # doctest: +SKIP
>>> from powergraph.plot.layout.view import format_share   # no matplotlib needed
>>> format_share(2063.26, 2270.0)
'90.9 %'
"""
