"""How a cavity network reaches the engine: lowered once and kept, or why it does not lower (a mixin of
:class:`exchange.network.network.Network`)."""
from __future__ import annotations

__all__ = ["NetworkLowering"]


class NetworkLowering:
    """Hooks used by :func:`cavity.integration.integrate` (``compiled_solver``, ``compiled_unsupported``) and by
    the results (``engine``); needs ``gas``, ``cavities``, ``exchanges`` and ``ambient``."""

    def compiled_solver(self):
        """This network lowered onto the engine (:func:`exchange.engine.lower.lower`), or None when a part of it is
        not supported there (:meth:`compiled_unsupported` says which). Built once and kept."""
        key = (type(self), self.gas, self.cavities, self.exchanges, self.ambient)
        cached = self.__dict__.get("_compiled")
        if cached is None or cached[0] is not key[0] or any(x is not y for x, y in zip(cached[1:], key[1:])) \
                or not _hosted_here(cached[-1], self):
            from exchange.engine.lower import lower

            cached = key + (lower(self),)
            self.__dict__["_compiled"] = cached
        return cached[-1]

    def engine(self):
        """:meth:`compiled_solver`, or a ValueError saying why this network does not lower."""
        fast = self.compiled_solver()
        if fast is None:
            raise ValueError(f"the engine cannot run {type(self).__name__}: {self.compiled_unsupported()}")
        return fast

    def compiled_unsupported(self) -> str | None:
        """Why :meth:`compiled_solver` is None (None: it is supported)."""
        from exchange.engine.lower import unsupported_reason

        return unsupported_reason(self)


def _hosted_here(fast, net) -> bool:
    """A lowered network's hosted parts are registered in this process for ``net`` (not, e.g., for the network
    it was copied or unpickled from): else it is lowered again (:mod:`exchange.engine.host`)."""
    if fast is None or fast.host < 0:
        return True
    from exchange.engine.host import HOSTS

    host = HOSTS.get(fast.host)
    return host is not None and host.network is net
