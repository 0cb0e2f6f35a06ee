// Checks an XDMF index against the HDF5 files it references: well-formed XML, a temporal
// collection, and every HDF DataItem names an existing file and dataset whose shape equals
// the declared Dimensions, whose type is the declared NumberType and Precision, and which
// has its "units" and "description" attributes. Returns the parsed tree for further checks.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "io/h5_util.hpp"
#include "mini_xml.hpp"
#include "scratch.hpp"

namespace cgdem::io::test {

inline std::vector<hsize_t> parse_dims(const std::string& s) {
  std::istringstream in(s);
  std::vector<hsize_t> d;
  for (hsize_t v; in >> v;) d.push_back(v);
  return d;
}

// Number of HDF DataItems verified is returned through `items`.
inline XmlNode check_xdmf(const std::string& xdmf_path, int& items) {
  const std::string dir = std::filesystem::path(xdmf_path).parent_path().string();
  XmlNode root = MiniXml::parse(slurp(xdmf_path));
  EXPECT_EQ(root.name, "Xdmf");
  auto grids = root.all("Grid");
  EXPECT_FALSE(grids.empty());
  if (!grids.empty()) {
    EXPECT_EQ(grids[0]->attr.at("GridType"), "Collection");
    EXPECT_EQ(grids[0]->attr.at("CollectionType"), "Temporal");
  }
  items = 0;
  for (const XmlNode* item : root.all("DataItem")) {
    if (item->attr.at("Format") != "HDF") continue;
    std::string text = item->text;
    text.erase(0, text.find_first_not_of(" \n"));
    text.erase(text.find_last_not_of(" \n") + 1);
    const size_t colon = text.find(':');
    EXPECT_NE(colon, std::string::npos) << text;
    const std::string file = dir + "/" + text.substr(0, colon), set = text.substr(colon + 1);
    EXPECT_TRUE(std::filesystem::exists(file)) << file;
    h5::Id f = h5::open_file(file);
    std::vector<hsize_t> dims;
    h5::read_double(f, set.substr(1), dims, file);
    EXPECT_EQ(dims, parse_dims(item->attr.at("Dimensions"))) << text;
    h5::Id ds(H5Dopen2(f, set.c_str(), H5P_DEFAULT), H5Dclose);
    h5::Id type(H5Dget_type(ds), H5Tclose);
    const std::string number = item->attr.at("NumberType");
    EXPECT_EQ(H5Tget_class(type), number == "Float" ? H5T_FLOAT : H5T_INTEGER) << text;
    EXPECT_EQ(std::to_string(H5Tget_size(type)), item->attr.at("Precision")) << text;
    const auto meta = h5::read_string_attributes(ds, file);
    EXPECT_TRUE(meta.count("units") && meta.count("description")) << text << ": no units/description";
    ++items;
  }
  return root;
}

}  // namespace cgdem::io::test
