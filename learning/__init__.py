"""The learned layers as estimators: features, datasets, the interception net, the pass tree.

Takes arrays, returns arrays; imports no pymunk, no rerun and nothing from `robotsoccer`.
"""
