"""The input/output layer, beside every other: what crosses the program's edge.

========================  ======================================================================
``inputs``                one parser for every number rockcli reads, and one splitter for every
                          ``key=value,...`` spec (each failure one sentence)
``units``                 SI inside, g only at the edges: standard gravity and the unit words
``output_checks``         output paths checked before any work, OS errors as one sentence
``files``                 the one output transaction: checked before the work, all written or none
========================  ======================================================================
"""
