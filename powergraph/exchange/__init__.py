"""Exchange formats (docs/exchange.md): REXS gear units written from a train
(:mod:`~powergraph.exchange.rexs_writer`, :mod:`~powergraph.exchange.rexs_text`; the
reader is the model layer's :mod:`powergraph.model.rexs_reader`), a REXS file imported as
a model file and duty-cycle points (:mod:`~powergraph.exchange.rexs_import`), and VECTO
gearbox files (:mod:`~powergraph.exchange.vgbx`)."""
