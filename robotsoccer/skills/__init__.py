"""Client skills: minds that act on percepts only, wrapping the learned layers into behaviours.

* :mod:`robotsoccer.skills.intercept` — layer 1 (paper §5): the interception defender with its
  behaviours (still, straight, random, net, lookup, analytic) and the drill's aimed shooter.
* :mod:`robotsoccer.skills.passing` — layer 2 (paper §6): the passer with its choosers (random,
  tree, boost, closest, analytic), the receivers that report their view, the waiting defenders.
* :mod:`robotsoccer.skills.shootout` — the demo's dribbling shooter and ball-chasing goalie.
"""
