# SPDX-License-Identifier: GPL-2.0-or-later
#
# Mesa Ethernet boards of the virtual board (included by
# sim/verilator/CMakeLists.txt): 7i92 and 7i96S.  Their hm2 firmwares are
# Verilated with the local-bus ones (their board files say bus =
# "localbus": the hm2 core sits on the Ethernet engine's internal bus);
# eth_board.cpp puts the FPGA flash and the LBP16 engine (lbp16.cpp) in
# front and udp.cpp serves LBP16 datagrams.  The Ethernet family comes
# first in the factory table, so it makes these boards.
set(VB_ETH_DIR ${CMAKE_CURRENT_SOURCE_DIR}/eth)
list(APPEND VBOARD_SOURCES ${VB_ETH_DIR}/lbp16.cpp ${VB_ETH_DIR}/eth_board.cpp
                           ${VB_ETH_DIR}/udp.cpp)
list(PREPEND VBOARD_FACTORIES vb_factory_eth)
