#!/bin/sh
# SPDX-License-Identifier: GPL-2.0-or-later
halstreamer bad.txt 2>&1
