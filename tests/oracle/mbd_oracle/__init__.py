"""The CasADi oracle of mbd: rebuilds each mechanism from its model JSON with CasADi and checks
mbd's generated functions against CasADi's own derivatives (see tests/oracle/README.md)."""
