// Malformed RT-STRUCTs, derived from pydicom's sample with DCMTK: each must be
// rejected as bad input with a message naming the reason.
#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>

#include "builder/import/import.h"
#include "tests/import/nifti_test_util.h"

namespace body {
namespace {

const char* kRtStruct = "/usr/lib/python3/dist-packages/pydicom/data/test_files/rtstruct.dcm";

std::string derive(const std::string& name, const std::function<void(DcmDataset&)>& edit) {
    DcmFileFormat file;
    EXPECT_TRUE(file.loadFile(kRtStruct).good());
    edit(*file.getDataset());
    const std::string path = test::temp_path(name);
    EXPECT_TRUE(file.saveFile(path.c_str(), EXS_LittleEndianExplicit).good());
    return path;
}

DcmItem* first_contour(DcmDataset& ds) {
    DcmItem* roi = nullptr;
    DcmItem* contour = nullptr;
    EXPECT_TRUE(ds.findAndGetSequenceItem(DCM_ROIContourSequence, roi, 0).good());
    EXPECT_TRUE(roi && roi->findAndGetSequenceItem(DCM_ContourSequence, contour, 0).good());
    return contour;
}

TEST(RtStructImport, MissingRoiContourSequenceIsBadInput) {
    if (!std::filesystem::exists(kRtStruct)) GTEST_SKIP() << "needs Debian package python3-pydicom";
    const std::string path = derive("no_roi_contours.dcm", [](DcmDataset& ds) {
        ASSERT_TRUE(ds.findAndDeleteElement(DCM_ROIContourSequence).good());
    });
    auto r = import_rtstruct(path, {});
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().exit_code, kExitBadInput);
    EXPECT_NE(r.error().message.find("ROI Contour Sequence"), std::string::npos) << r.error().message;
}

TEST(RtStructImport, NonAxialContourPlaneIsAClearError) {
    if (!std::filesystem::exists(kRtStruct)) GTEST_SKIP() << "needs Debian package python3-pydicom";
    const std::string path = derive("tilted.dcm", [](DcmDataset& ds) {
        DcmItem* c = first_contour(ds);
        ASSERT_NE(c, nullptr);
        ASSERT_TRUE(c->putAndInsertString(DCM_ContourData, "0\\0\\0\\10\\0\\5\\10\\10\\5").good());
        ASSERT_TRUE(c->putAndInsertString(DCM_NumberOfContourPoints, "3").good());
    });
    auto r = import_rtstruct(path, {});
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().exit_code, kExitBadInput);
    EXPECT_NE(r.error().message.find("not axial"), std::string::npos) << r.error().message;
    EXPECT_NE(r.error().message.find("patient"), std::string::npos) << r.error().message;
}

TEST(RtStructImport, PointCountThatDisagreesWithTheDataIsRefused) {
    if (!std::filesystem::exists(kRtStruct)) GTEST_SKIP() << "needs Debian package python3-pydicom";
    const std::string path = derive("count.dcm", [](DcmDataset& ds) {
        DcmItem* c = first_contour(ds);
        ASSERT_NE(c, nullptr);
        ASSERT_TRUE(c->putAndInsertString(DCM_ContourData, "0\\0\\5\\10\\0\\5\\10\\10\\5").good());
        ASSERT_TRUE(c->putAndInsertString(DCM_NumberOfContourPoints, "7").good());
    });
    auto r = import_rtstruct(path, {});
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().exit_code, kExitBadInput);
    EXPECT_NE(r.error().message.find("Number of Contour Points (3006,0046) is 7 but Contour Data holds 3 points"),
              std::string::npos)
        << r.error().message;
}

TEST(RtStructImport, OtherModalitiesAndGarbageAreRejected) {
    if (!std::filesystem::exists(kRtStruct)) GTEST_SKIP() << "needs Debian package python3-pydicom";
    const std::string ct = derive("ct.dcm", [](DcmDataset& ds) { ds.putAndInsertString(DCM_Modality, "CT"); });
    auto r = import_rtstruct(ct, {});
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("RTSTRUCT"), std::string::npos);
    const std::string junk = test::temp_path("junk.dcm");
    {
        std::FILE* f = std::fopen(junk.c_str(), "wb");
        std::fputs("not dicom at all", f);
        std::fclose(f);
    }
    r = import_rtstruct(junk, {});
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().exit_code, kExitBadInput);
}

}  // namespace
}  // namespace body
