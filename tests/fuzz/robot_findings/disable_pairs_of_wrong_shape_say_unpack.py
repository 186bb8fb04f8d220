"""Robot.disable_pairs with an entry that is not a pair of names (three names, or a string
passed instead of a list of pairs) raises Python's "too many values to unpack" / "not enough
values to unpack": the message names neither the argument nor the entry.

Census: robots corpus, family "argument", group "tables" (error-type, "unclear").
"""

import swarmcollide as sc

box = sc.Box([0.1, 0.1, 0.1])
robot = sc.Robot(["a", "b"], [sc.Joint("j", "revolute", 0, 1, lower=-1, upper=1)],
                 [("g", 0, None, box), ("h", 1, None, box)])
for pairs in ([("a", "b", "a")], "ab"):
    try:
        robot.disable_pairs(pairs)
        print(f"disable_pairs({pairs!r}): accepted")
    except ValueError as error:
        print(f"disable_pairs({pairs!r}): ValueError: {error}")
