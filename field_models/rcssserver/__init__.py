"""The ``rcssserver`` field model: a Soccer Server driven over UDP in its own protocol.

* :mod:`~field_models.rcssserver.model` — the registry entry and the preset (which server:
  ours served in-process, one at an address, or a real rcssserver binary to start);
* :mod:`~field_models.rcssserver.arena` — :class:`~field_models.rcssserver.arena.WireArena`: the
  coach through a trainer connection, each player a client in synch mode;
* :mod:`~field_models.rcssserver.client` — the minimal UDP client both use;
* :mod:`~field_models.rcssserver.bench` — cycles per second over the wire beside in-process.
"""
