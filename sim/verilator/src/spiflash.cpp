// SPDX-License-Identifier: GPL-2.0-or-later
//
// spiflash.cpp - the SPI NOR flash model (spiflash.h).
#include "spiflash.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace vb {

namespace {
// Typical times from the parts' data sheets (ST/Micron M25Pxx).
const FlashPart kParts[] = {
    {"m25p16", {0x20, 0x20, 0x15}, 0x14, 2u << 20, 0x10000, 256, 640000, 600000000ull,
     13000000000ull, 1500000},
    {"m25p32", {0x20, 0x20, 0x16}, 0x15, 4u << 20, 0x10000, 256, 640000, 600000000ull,
     23000000000ull, 1500000},
    // M25P10-A: 1 Mbit, four 32 KiB sectors (small: the whole-flash tests)
    {"m25p10", {0x20, 0x20, 0x11}, 0x10, 128u << 10, 0x8000, 256, 1400000, 650000000ull,
     1700000000ull, 5000000},
};

enum : uint8_t {
    CMD_WRSR = 0x01,
    CMD_PP = 0x02,
    CMD_READ = 0x03,
    CMD_WRDI = 0x04,
    CMD_RDSR = 0x05,
    CMD_WREN = 0x06,
    CMD_FAST_READ = 0x0B,
    CMD_RDID = 0x9F,
    CMD_RES = 0xAB,
    CMD_BE = 0xC7,
    CMD_SE = 0xD8,
};
} // namespace

const FlashPart *flash_part(const std::string &name)
{
    for (const FlashPart &p : kParts)
        if (name == p.name)
            return &p;
    return nullptr;
}

std::string flash_part_names()
{
    std::string s;
    for (const FlashPart &p : kParts)
        s += (s.empty() ? "" : ", ") + std::string(p.name);
    return s;
}

SpiFlash::~SpiFlash()
{
    if (mapped_ && mem_)
        munmap(mem_, map_len_);
}

int SpiFlash::open(const FlashPart &part, const std::string &path, bool &created,
                   std::string &err)
{
    part_ = &part;
    created = false;
    if (path.empty()) {
        own_.assign(part.size, 0xFF);
        mem_ = own_.data();
        created = true;
        return 0;
    }
    int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
        err = "flash file " + path + ": " + std::strerror(errno);
        return -errno;
    }
    int rc = 0;
    struct stat st;
    void *m = MAP_FAILED;
    if (fstat(fd, &st) != 0) {
        rc = -errno;
        err = "flash file " + path + ": " + std::strerror(errno);
        goto out;
    }
    if (st.st_size == 0) {
        if (ftruncate(fd, part.size) != 0) {
            rc = -errno;
            err = "flash file " + path + ": cannot size it: " + std::strerror(errno);
            goto out;
        }
        created = true;
    } else if (static_cast<uint64_t>(st.st_size) != part.size) {
        rc = -EINVAL;
        err = "flash file " + path + " has " + std::to_string(st.st_size) + " bytes, an " +
              part.name + " holds " + std::to_string(part.size);
        goto out;
    }
    m = mmap(nullptr, part.size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    if (m == MAP_FAILED) {
        rc = -errno;
        err = "flash file " + path + ": mmap: " + std::strerror(errno);
        goto out;
    }
    mem_ = static_cast<uint8_t *>(m);
    map_len_ = part.size;
    mapped_ = true;
    if (created)
        std::memset(mem_, 0xFF, part.size);
out:
    ::close(fd);
    return rc;
}

void SpiFlash::poke(uint32_t addr, const uint8_t *p, size_t n)
{
    if (addr >= part_->size)
        return;
    if (n > part_->size - addr)
        n = part_->size - addr;
    std::memcpy(mem_ + addr, p, n);
}

bool SpiFlash::is_protected(uint32_t addr, uint32_t len) const
{
    if (bp_ == 0)
        return false;
    // BP = n protects the upper 1/2^(6-n) of the array (n >= 6: all of it),
    // as on the M25P16 (32 sectors: BP=1 the top sector ... BP=6 all).
    uint32_t sectors = part_->size / part_->sector;
    uint32_t prot = bp_ >= 6 ? sectors : (1u << (bp_ - 1)) * (sectors / 32 ? sectors / 32 : 1);
    if (prot > sectors)
        prot = sectors;
    uint32_t first = (sectors - prot) * part_->sector;
    return addr + len > first;
}

void SpiFlash::sync(uint64_t now)
{
    if (pending_.kind == Pending::NONE || now < pending_.done_ns)
        return;
    switch (pending_.kind) {
    case Pending::PROGRAM:
        for (uint32_t i = 0; i < pending_.len; i++) {
            uint32_t a = (pending_.addr & ~(part_->page - 1)) +
                         ((pending_.addr + i) & (part_->page - 1));
            mem_[a] &= pending_.bytes[i]; // programming only clears bits
        }
        break;
    case Pending::ERASE:
        std::memset(mem_ + pending_.addr, 0xFF, pending_.len);
        break;
    case Pending::STATUS:
        bp_ = pending_.status;
        break;
    case Pending::NONE: break;
    }
    pending_ = Pending{};
    wel_ = false;
}

bool SpiFlash::busy(uint64_t now)
{
    sync(now);
    return pending_.kind != Pending::NONE;
}

uint8_t SpiFlash::status_byte(uint64_t now)
{
    bool wip = busy(now);
    return static_cast<uint8_t>((wip ? 1u : 0u) | (wel_ ? 2u : 0u) | (bp_ << 2));
}

void SpiFlash::start(Pending p, uint64_t busy_ns, uint64_t now)
{
    p.done_ns = now + busy_ns / speedup_;
    pending_ = std::move(p);
    if (pending_.kind == Pending::ERASE) {
        // Half of the cells are erased right away: an interrupted erase
        // leaves the range neither old nor erased.
        std::memset(mem_ + pending_.addr, 0xFF, pending_.len / 2);
    }
    sync(now); // a zero busy time completes at once
}

void SpiFlash::select(bool active, uint64_t now)
{
    sync(now);
    if (active) {
        selected_ = true;
        cmd_.clear();
        return;
    }
    if (!selected_)
        return;
    selected_ = false;
    execute(now);
    cmd_.clear();
}

// /S went high: commands that act at the end of the frame.
void SpiFlash::execute(uint64_t now)
{
    if (cmd_.empty() || busy(now))
        return; // only RDSR is served while busy; writes are ignored
    uint8_t op = cmd_[0];
    size_t n = cmd_.size();
    auto addr24 = [this]() {
        return (static_cast<uint32_t>(cmd_[1]) << 16 | static_cast<uint32_t>(cmd_[2]) << 8 |
                cmd_[3]) & (part_->size - 1);
    };
    switch (op) {
    case CMD_WREN:
        if (n == 1)
            wel_ = true;
        break;
    case CMD_WRDI:
        if (n == 1)
            wel_ = false;
        break;
    case CMD_WRSR:
        if (n == 2 && wel_) {
            Pending p;
            p.kind = Pending::STATUS;
            p.status = static_cast<uint8_t>((cmd_[1] >> 2) & 7u);
            start(std::move(p), part_->t_w_ns, now);
        }
        break;
    case CMD_PP: {
        if (n < 5 || !wel_)
            break;
        uint32_t a = addr24();
        if (is_protected(a & ~(part_->page - 1), part_->page)) {
            wel_ = false;
            break;
        }
        Pending p;
        p.kind = Pending::PROGRAM;
        p.addr = a;
        size_t data = n - 4;
        // More than a page: only the last `page` bytes are kept.
        size_t skip = data > part_->page ? data - part_->page : 0;
        p.len = static_cast<uint32_t>(data - skip);
        p.bytes.assign(cmd_.begin() + 4 + static_cast<long>(skip), cmd_.end());
        start(std::move(p), part_->t_pp_ns, now);
        break;
    }
    case CMD_SE: {
        if (n != 4 || !wel_)
            break;
        uint32_t a = addr24() & ~(part_->sector - 1);
        if (is_protected(a, part_->sector)) {
            wel_ = false;
            break;
        }
        Pending p;
        p.kind = Pending::ERASE;
        p.addr = a;
        p.len = part_->sector;
        start(std::move(p), part_->t_se_ns, now);
        break;
    }
    case CMD_BE: {
        if (n != 1 || !wel_)
            break;
        if (bp_ != 0) {
            wel_ = false;
            break;
        }
        Pending p;
        p.kind = Pending::ERASE;
        p.addr = 0;
        p.len = part_->size;
        start(std::move(p), part_->t_be_ns, now);
        break;
    }
    default: break;
    }
}

uint8_t SpiFlash::transfer(uint8_t mosi, uint64_t now)
{
    sync(now);
    if (!selected_)
        return 0xFF; // /S high: the output is high impedance (pulled up)
    cmd_.push_back(mosi);
    size_t pos = cmd_.size() - 1; // index of this byte in the frame
    uint8_t op = cmd_[0];
    if (pos == 0)
        return 0xFF;
    if (op == CMD_RDSR)
        return status_byte(now);
    if (pending_.kind != Pending::NONE)
        return 0xFF; // busy: nothing but RDSR answers
    switch (op) {
    case CMD_RDID:
        return pos <= 3 ? part_->jedec[pos - 1] : 0x00;
    case CMD_RES:
        return pos >= 4 ? part_->signature : 0xFF;
    case CMD_READ:
    case CMD_FAST_READ: {
        size_t first = op == CMD_READ ? 4 : 5; // FAST_READ has a dummy byte
        if (pos == 3)
            read_addr_ = (static_cast<uint32_t>(cmd_[1]) << 16 |
                          static_cast<uint32_t>(cmd_[2]) << 8 | cmd_[3]) & (part_->size - 1);
        if (pos < first)
            return 0xFF;
        uint8_t v = mem_[read_addr_];
        read_addr_ = (read_addr_ + 1) & (part_->size - 1);
        // Reads do not keep the frame: a whole-flash read stays small.
        cmd_.resize(first);
        return v;
    }
    default:
        if (op == CMD_PP && cmd_.size() > 4 + 4 * part_->page)
            cmd_.erase(cmd_.begin() + 4, cmd_.begin() + 4 + part_->page);
        return 0xFF;
    }
}

} // namespace vb
