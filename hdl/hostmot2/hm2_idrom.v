// SPDX-License-Identifier: GPL-2.0-or-later
//
// hm2_idrom: the ID block, the IDROM and the IDROM write enable
// (spec/hostmot2.md sections 1-5).
//
//   0x0100 + 16k  ID block, A3..A2 select (the page aliases every 16 bytes):
//                 0x55AACAFE, "HOST", "MOT2", IDROM offset 0x400     R
//   0x0400-0x07FF IDROM, 256 x 32 bit                                R (W when enabled)
//   0x0800        bit 0 = IDROM write enable (1 = writable)          R/W
//
// The IDROM is a RAM loaded from the IDROM parameter when the FPGA is
// configured (the initial block), as a block RAM is on real hardware; the
// generator (tools/hm2gen) computes the image from the firmware description,
// so nothing in it is typed by hand.  Reset clears the write enable but not
// the RAM, again like the real firmware: only reconfiguration reloads it.
`default_nettype none

module hm2_idrom #(
    parameter [8191:0] IDROM = {8192{1'b0}}  // word k in bits 32k+31..32k
) (
    input  wire        clk,
    input  wire        rst,
    // Byte address; bits 1:0 are ignored (aligned 32-bit accesses only).
    /* verilator lint_off UNUSEDSIGNAL */
    input  wire [15:0] bus_addr,
    /* verilator lint_on UNUSEDSIGNAL */
    input  wire [31:0] bus_wdata,
    input  wire        bus_we,
    input  wire        bus_re,
    output reg  [31:0] bus_rdata
);
    localparam [31:0] COOKIE     = 32'h55AACAFE;
    localparam [31:0] NAME_LOW   = 32'h54534F48;  // "HOST"
    localparam [31:0] NAME_HIGH  = 32'h32544F4D;  // "MOT2"
    localparam [31:0] IDROM_PTR  = 32'h00000400;

    reg [31:0] mem [0:255];
    reg        wen_q;

    integer k;
    initial begin
        for (k = 0; k < 256; k = k + 1)
            mem[k] = IDROM[k*32 +: 32];
    end

    wire [7:0] page     = bus_addr[15:8];
    wire       sel_id   = (page == 8'h01);
    wire       sel_rom  = (page[7:2] == 6'b000001);  // 0x0400-0x07FF
    wire       sel_wen  = (page == 8'h08) && (bus_addr[7:2] == 6'd0);
    wire [7:0] word     = bus_addr[9:2];

    reg [31:0] id_word;
    always @(*) begin
        case (bus_addr[3:2])
            2'd0:    id_word = COOKIE;
            2'd1:    id_word = NAME_LOW;
            2'd2:    id_word = NAME_HIGH;
            default: id_word = IDROM_PTR;
        endcase
    end

    // RAM port: synchronous write, synchronous read with enable (block-RAM
    // style); the read register only loads on bus_re, so the data is held
    // until the next read as the bus convention requires.
    reg [31:0] rom_q;
    always @(posedge clk) begin
        if (bus_we && sel_rom && wen_q)
            mem[word] <= bus_wdata;
        if (bus_re)
            rom_q <= mem[word];
    end

    reg        rd_rom_q;
    reg [31:0] rd_other_q;
    always @(posedge clk) begin
        if (rst) begin
            wen_q      <= 1'b0;
            rd_rom_q   <= 1'b0;
            rd_other_q <= 32'd0;
        end else begin
            if (bus_we && sel_wen)
                wen_q <= bus_wdata[0];
            if (bus_re) begin
                rd_rom_q   <= sel_rom;
                rd_other_q <= sel_id  ? id_word :
                              sel_wen ? {31'd0, wen_q} : 32'd0;
            end
        end
    end

    always @(*) begin
        bus_rdata = rd_rom_q ? rom_q : rd_other_q;
    end
endmodule

`default_nettype wire
