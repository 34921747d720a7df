#!/usr/bin/env bash
# A line-rate flood of ring frames against class 1 production (net_dlr_ring.py, phase "flood").
exec "$(dirname "$0")/net_dlr_ring.sh" flood
