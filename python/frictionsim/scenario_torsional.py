"""Replaced: the torsional scenario support is the ``torsional`` rig kind of :mod:`frictionsim.scenario`."""

raise ImportError("frictionsim.scenario_torsional was replaced by the scenario package's rig-kind registry: use "
                  "frictionsim.scenario.rig_kind('torsional') (its keys, builder, analysis and plots) and "
                  "frictionsim.scenario.LimitCycleRun (was TorsionalCaseRun)")
